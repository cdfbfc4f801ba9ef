// Writers and readers keep the geometry: a volume with odd sizes, anisotropic spacing and an
// oblique direction matrix comes back with every voxel at the same world position.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/core/Orientation.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"

namespace mvw::io {
namespace {

namespace fs = std::filesystem;

Volume makePhantom(ScalarType type, bool leftHanded, int components = 1) {
  glm::dmat3 dir =
      glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.4, glm::normalize(glm::dvec3(1, -2, 0.5))));
  if (leftHanded) dir[1] = -dir[1];
  // Intentional odd sizes: catch row/column mix-ups that square volumes hide.
  Volume v({7, 5, 3}, components, type,
           makeWorldFromIndex({-12.5, 40.25, 3.0}, {0.8, 1.3, 2.7}, dir));
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 7; ++i)
        for (int c = 0; c < components; ++c) v.setValue(i, j, k, c, i + 10 * j + 50 * k + 3 * c);
  return v;
}

// Every voxel of `a` has the same value at the same world position in `b`.
void expectSameWorldContent(const Volume& a, const Volume& b, double tolMm) {
  ASSERT_EQ(a.voxelCount(), b.voxelCount());
  ASSERT_EQ(a.components(), b.components());
  const glm::dmat4 bIndexFromWorld = glm::inverse(b.worldFromIndex());
  const glm::ivec3 d = a.dimensions();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const glm::dvec3 w = a.worldFromIndexPoint({i, j, k});
        const glm::dvec3 ijk = glm::dvec3(bIndexFromWorld * glm::dvec4(w, 1.0));
        const glm::ivec3 n(std::lround(ijk.x), std::lround(ijk.y), std::lround(ijk.z));
        ASSERT_LT(glm::length(b.worldFromIndexPoint(glm::dvec3(n)) - w), tolMm)
            << i << "," << j << "," << k;
        for (int c = 0; c < a.components(); ++c)
          ASSERT_EQ(a.value(i, j, k, c), b.value(n.x, n.y, n.z, c));
      }
}

class RoundTrip : public ::testing::TestWithParam<std::tuple<std::string, ScalarType, bool>> {};

TEST_P(RoundTrip, KeepsGeometryAndVoxels) {
  const auto& [ext, type, leftHanded] = GetParam();
  const Volume v = makePhantom(type, leftHanded);
  const fs::path file = test::scratchDir() / ("phantom" + ext);
  writeVolume(v, file);
  const Volume r = readVolume(file);
  EXPECT_EQ(r.scalarType(), type);
  EXPECT_EQ(r.dimensions(), v.dimensions());
  // NIfTI stores the matrix in float32; MetaImage as decimal text with 17 digits.
  const double tol = ext == ".mha" || ext == ".mhd" ? 1e-9 : 1e-4;
  expectSameWorldContent(v, r, tol);
  if (!leftHanded) {
    for (int c = 0; c < 4; ++c)
      for (int rr = 0; rr < 4; ++rr)
        EXPECT_NEAR(r.worldFromIndex()[c][rr], v.worldFromIndex()[c][rr], tol);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Formats, RoundTrip,
    ::testing::Combine(::testing::Values(".nii", ".nii.gz", ".mha", ".mhd"),
                       ::testing::Values(ScalarType::Int16, ScalarType::Float32, ScalarType::UInt8),
                       ::testing::Bool()),
    [](const auto& param) {
      std::string ext = std::get<0>(param.param).substr(1);
      for (auto& ch : ext)
        if (ch == '.') ch = '_';
      return ext + "_" + std::string(scalarName(std::get<1>(param.param))) +
             (std::get<2>(param.param) ? "_lefthanded" : "_righthanded");
    });

TEST(RoundTrip, FourDimensionalNiftiKeepsFramesAsComponents) {
  const Volume v = makePhantom(ScalarType::Int16, false, 4);
  const fs::path file = test::scratchDir() / "frames.nii.gz";
  writeVolume(v, file);
  const Volume r = readVolume(file);
  EXPECT_EQ(r.components(), 4);
  expectSameWorldContent(v, r, 1e-4);
}

// A statistic map names its statistic by the NIfTI intent code (bytes 68-69 of a NIfTI-1
// header): z for NIFTI_INTENT_ZSCORE (5), t for NIFTI_INTENT_TTEST (3).
TEST(RoundTrip, NiftiIntentCodeNamesTheStatistic) {
  const auto dir = test::scratchDir();
  Volume v({4, 4, 4}, 1, ScalarType::Float32, glm::dmat4(1.0));
  for (const auto& [code, unit] : {std::pair{5, "z"}, std::pair{3, "t"}, std::pair{0, ""}}) {
    const auto file = dir / ("stat" + std::to_string(code) + ".nii");
    writeVolume(v, file);
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    const char bytes[2] = {static_cast<char>(code), 0};  // little endian, as written
    f.seekp(68);
    f.write(bytes, 2);
    f.close();
    EXPECT_EQ(readVolume(file).metadata().unit, unit) << code;
  }
}

TEST(RoundTrip, WriterLeavesNoPartialFileOnError) {
  const fs::path dir = test::scratchDir();
  const Volume v = makePhantom(ScalarType::Int16, false);
  EXPECT_THROW(writeVolume(v, dir / "missing-folder" / "x.nii.gz"), Error);
  EXPECT_THROW(writeVolume(v, dir / "x.png"), InputError);
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace mvw::io
