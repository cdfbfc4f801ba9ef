// The DICOM writers of modules/dicomout against mvw's own SEG reader: a binary SEG on an oblique,
// anisotropic grid read back gives every voxel of every segment and the grid itself (the slices
// that hold a voxel); UIDs are
// new, valid and under the root asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "mvw/core/Error.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SegmentationWriter.h"
#include "mvw/io/DicomSeg.h"

namespace {

namespace fs = std::filesystem;
using namespace mvw;

fs::path tempDir() {
  const fs::path d =
      fs::temp_directory_path() / ("mvw-dicomout-test-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

Volume obliqueGrid() {
  const glm::dmat4 rot =
      glm::rotate(glm::dmat4(1.0), 0.3, glm::normalize(glm::dvec3(0.2, 1.0, 0.4)));
  const glm::dmat3 dir(rot);
  Volume v({23, 17, 9}, 1, ScalarType::Float32,
           makeWorldFromIndex({-40.5, 12.25, 7.0}, {1.5, 0.75, 3.25}, dir));
  return v;
}

TEST(DicomOut, SegReadBackVoxelForVoxel) {
  const Volume grid = obliqueGrid();
  const glm::ivec3 d = grid.dimensions();
  // A ball and a thin slab that share voxels and leave slices empty.
  dicomout::SegmentMask ball{"ball", "an off-centre ball", {}, false};
  dicomout::SegmentMask slab{"", "", {}, true};
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const glm::dvec3 p(i - 8.0, j - 9.0, (k - 5.0) * 2.0);
        if (glm::dot(p, p) < 36.0) ball.voxels.push_back(grid.linearIndex(i, j, k));
        if (k >= 2 && k <= 3 && i > 15) slab.voxels.push_back(grid.linearIndex(i, j, k));
      }
  ASSERT_GT(ball.voxels.size(), 50u);
  const fs::path file = tempDir() / "roundtrip.dcm";
  dicomout::SeriesInfo series{"", 3001, "mvw test"};
  const dicomout::DicomIdentity id = dicomout::identityOf(grid, {"TEST-1", "Test^Seg"});
  EXPECT_FALSE(id.fromDicom);
  dicomout::writeSegmentation(file, grid, {ball, slab}, id, series, "mvw unit test");

  // Only the slices that hold a voxel of a segment are frames: the ball's 5 and the slab's 2.
  std::set<int> ballSlices, slabSlices;
  for (std::size_t v : ball.voxels) ballSlices.insert(static_cast<int>(v / (d.x * d.y)));
  for (std::size_t v : slab.voxels) slabSlices.insert(static_cast<int>(v / (d.x * d.y)));
  EXPECT_EQ(ballSlices.size() + slabSlices.size(), 7u);
  const int first = std::min(*ballSlices.begin(), *slabSlices.begin());
  const int last = std::max(*ballSlices.rbegin(), *slabSlices.rbegin());

  const io::Segmentation seg = io::readDicomSegmentation(file);
  EXPECT_EQ(seg.frames, 7);
  ASSERT_EQ(seg.segments.size(), 2u);
  EXPECT_EQ(seg.segments[0].label, "ball");
  EXPECT_EQ(seg.segments[1].label, "Neoplasm");  // no label of its own: its type's code meaning
  EXPECT_EQ(seg.type, "BINARY");
  EXPECT_EQ(seg.frameOfReferenceUid, id.frameOfReferenceUid);
  // The grid read back spans the slices that have frames, on the written grid's lattice.
  ASSERT_EQ(seg.masks.dimensions(), glm::ivec3(d.x, d.y, last - first + 1));
  const glm::dmat4 shifted =
      grid.worldFromIndex() * glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, first));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(seg.masks.worldFromIndex()[c][r], shifted[c][r], 1e-6)
          << "worldFromIndex[" << c << "][" << r << "]";
  std::size_t differ = 0;
  for (int s = 0; s < 2; ++s) {
    const auto& voxels = (s == 0 ? ball : slab).voxels;
    const std::set<std::size_t> in(voxels.begin(), voxels.end());
    for (int k = first; k <= last; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i)
          differ += (seg.masks.value(i, j, k - first, s) != 0) !=
                    (in.count(grid.linearIndex(i, j, k)) > 0);
  }
  EXPECT_EQ(differ, 0u);
  if (!::testing::Test::HasFailure()) fs::remove_all(file.parent_path());
}

TEST(DicomOut, EmptySegmentationIsRefused) {
  const Volume grid = obliqueGrid();
  const dicomout::DicomIdentity id = dicomout::identityOf(grid, {"TEST-1", "Test^Seg"});
  const fs::path file = tempDir() / "empty.dcm";
  EXPECT_THROW(dicomout::writeSegmentation(file, grid, {{"none", "", {}, false}}, id, {}, "x"),
               InputError);
  EXPECT_FALSE(fs::exists(file));
  fs::remove_all(file.parent_path());
}

TEST(DicomOut, NoIdentityWithoutPatientIdAndName) {
  const Volume grid = obliqueGrid();
  EXPECT_THROW(dicomout::identityOf(grid), InputError);
  EXPECT_THROW(dicomout::identityOf(grid, {"ID", ""}), InputError);
  const auto a = dicomout::identityOf(grid, {"ID", "Name"});
  const auto b = dicomout::identityOf(grid, {"ID", "Name"});
  EXPECT_NE(a.studyInstanceUid, b.studyInstanceUid);  // a new study each time
}

TEST(DicomOut, UidsAreNewAndValid) {
  const std::regex uid("^2\\.25\\.(0|[1-9][0-9]*)$");
  std::set<std::string> seen;
  for (int n = 0; n < 2000; ++n) {
    const std::string u = dicomout::newUid();
    EXPECT_TRUE(std::regex_match(u, uid)) << u;
    EXPECT_LE(u.size(), 64u) << u;
    seen.insert(u);
  }
  EXPECT_EQ(seen.size(), 2000u);
  const std::string root = "1.2.826.0.1.3680043.10.543";
  const std::string rooted = dicomout::newUid(root);
  EXPECT_EQ(rooted.rfind(root + ".", 0), 0u) << rooted;
  EXPECT_LE(rooted.size(), 64u);
  EXPECT_NE(rooted.back(), '.');
  EXPECT_NO_THROW(dicomout::checkUidRoot(root, "--uid-root"));
  EXPECT_THROW(dicomout::checkUidRoot("1.02.3", "--uid-root"), InputError);
  EXPECT_THROW(dicomout::checkUidRoot("1..3", "--uid-root"), InputError);
  EXPECT_THROW(dicomout::checkUidRoot("1.2.a", "--uid-root"), InputError);
}

}  // namespace
