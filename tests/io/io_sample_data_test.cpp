// Real files from Debian's archive (scripts/fetch-sample-data): the Cranium CT as a DICOM
// series against the NIfTI it was made from, the big-endian nipy/nibabel NIfTI checked voxel
// by voxel against its own header, 4D fMRI, the atlases, and series selection in a folder.
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/core/Orientation.h"
#include "mvw/io/VolumeReader.h"

namespace mvw::io {
namespace {

namespace fs = std::filesystem;

TEST(SampleData, CraniumDicomSeriesEqualsItsNifti) {
  const Volume dicom = readVolume(test::sampleData("cranium/dicom"));
  const Volume nifti = readVolume(test::sampleData("cranium/cranium.nii.gz"));
  ASSERT_EQ(dicom.dimensions(), glm::ivec3(256, 256, 108));
  ASSERT_EQ(nifti.dimensions(), dicom.dimensions());
  ASSERT_EQ(dicom.scalarType(), nifti.scalarType());
  ASSERT_EQ(dicom.byteSize(), nifti.byteSize());
  EXPECT_EQ(std::memcmp(dicom.data(), nifti.data(), dicom.byteSize()), 0) << "voxels differ";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(dicom.worldFromIndex()[c][r], nifti.worldFromIndex()[c][r], 1e-4)
          << c << "," << r;
  EXPECT_EQ(orientationCode(dicom.direction()), "LPS");
  EXPECT_NEAR(dicom.spacing().x, 0.9570312, 1e-6);
  EXPECT_NEAR(dicom.spacing().z, 1.5, 1e-6);
  const auto [lo, hi] = dicom.valueRange();
  EXPECT_EQ(lo, -1024);
  EXPECT_EQ(hi, 2986);  // main.plist says 3033, the voxels say 2986
  EXPECT_EQ(dicom.metadata().modality, "CT");
  EXPECT_EQ(dicom.metadata().unit, "HU");
  EXPECT_EQ(dicom.metadata().seriesDescription, "Cranium CT");
  ASSERT_TRUE(dicom.metadata().sliceSpacing.has_value());
  EXPECT_TRUE(dicom.metadata().sliceSpacing->regular);
  EXPECT_EQ(dicom.metadata().sliceSpacing->slices, 108);
  EXPECT_NEAR(dicom.metadata().sliceSpacing->nominal, 1.5, 1e-4);
}

template <class T>
T bigEndian(const std::string& bytes, std::size_t offset) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, bytes.data() + offset, sizeof(T));
  std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

TEST(SampleData, BigEndianNiftiMatchesItsHeaderVoxelByVoxel) {
  // nibabel's anatomical.nii: big-endian int16, qfac = -1 (VTK reverses the slices).
  const fs::path path = test::sampleData("nibabel/anatomical.nii");
  std::ifstream in(path, std::ios::binary);
  const std::string raw{std::istreambuf_iterator<char>(in), {}};
  ASSERT_EQ(bigEndian<int>(raw, 0), 348);
  const int nx = bigEndian<short>(raw, 42), ny = bigEndian<short>(raw, 44),
            nz = bigEndian<short>(raw, 46);
  const auto voxOffset = static_cast<std::size_t>(bigEndian<float>(raw, 108));
  glm::dmat4 rasFromFileIndex(1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      rasFromFileIndex[c][r] = bigEndian<float>(raw, 280 + 16 * r + 4 * c);

  const Volume v = readVolume(path);
  ASSERT_EQ(v.dimensions(), glm::ivec3(nx, ny, nz));
  const glm::dmat4 indexFromWorld = glm::inverse(v.worldFromIndex());
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        glm::dvec4 w = rasFromFileIndex * glm::dvec4(i, j, k, 1.0);
        w.x = -w.x;  // RAS -> LPS
        w.y = -w.y;
        const glm::dvec3 ijk(indexFromWorld * w);
        const glm::ivec3 n(std::lround(ijk.x), std::lround(ijk.y), std::lround(ijk.z));
        ASSERT_LT(glm::length(ijk - glm::dvec3(n)), 1e-3) << "voxel " << i << "," << j << "," << k;
        const short expected = bigEndian<short>(raw, voxOffset + 2 * (i + nx * (j + ny * k)));
        ASSERT_EQ(v.value(n.x, n.y, n.z), expected) << "voxel " << i << "," << j << "," << k;
      }
  EXPECT_EQ(v.metadata().format, "NIfTI-1");
}

TEST(SampleData, FourDimensionalFmriKeepsItsFrames) {
  const Volume f = readVolume(test::sampleData("nipy/functional.nii.gz"));
  EXPECT_EQ(f.dimensions(), glm::ivec3(17, 21, 3));
  EXPECT_EQ(f.components(), 20);
  EXPECT_NEAR(f.spacing().z, 8.0, 1e-6);
}

TEST(SampleData, AtlasAndTemplateLoadInTheSameFrame) {
  const Volume t1 = readVolume(test::sampleData("mricron/ch2better.nii.gz"));
  const Volume aal = readVolume(test::sampleData("mricron/aal.nii.gz"));
  EXPECT_NEAR(t1.spacing().x, 0.5, 1e-6);
  EXPECT_NEAR(aal.spacing().x, 1.0, 1e-6);
  EXPECT_TRUE(isInteger(aal.scalarType()));
  // Both are MNI-space images: their centres lie within a few centimetres of each other.
  auto centre = [](const Volume& v) {
    return v.worldFromIndexPoint(glm::dvec3(v.dimensions() - 1) * 0.5);
  };
  EXPECT_LT(glm::length(centre(t1) - centre(aal)), 30.0);
}

// pydicom's deflated file (Deflated Explicit VR Little Endian): inflated by mvw before
// vtk-dicom reads it. Reference values from pydicom (pixel sum 33322688; (row, column)
// (0,0) = 213, (100,200) = 41, (511,3) = 115).
TEST(SampleData, DeflatedDicomIsInflatedAndMatchesPydicom) {
  const mvw::Volume v =
      mvw::io::readVolume(mvw::test::sampleData("pydicom/test_files/image_dfl.dcm"));
  ASSERT_EQ(v.dimensions(), glm::ivec3(512, 512, 1));
  double sum = 0;
  for (int j = 0; j < 512; ++j)
    for (int i = 0; i < 512; ++i) sum += v.value(i, j, 0);
  EXPECT_EQ(sum, 33322688.0);
  EXPECT_EQ(v.value(0, 0, 0), 213);
  EXPECT_EQ(v.value(200, 100, 0), 41);
  EXPECT_EQ(v.value(3, 511, 0), 115);
  EXPECT_EQ(v.metadata().sourcePath,
            mvw::test::sampleData("pydicom/test_files/image_dfl.dcm").string());
}

TEST(SampleData, FolderWithTwoSeriesNeedsAChoice) {
  const fs::path dir = test::scratchDir();
  fs::copy(test::sampleData("cranium/dicom"), dir / "ct");
  const std::string cmd = "niftitodicom -s -o '" + (dir / "t1").string() +
                          "' --modality MR --series-number 7 --series-description 'T1 test' '" +
                          test::sampleData("nipy/anatomical.nii.gz").string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const auto all = readAllVolumes(dir);
  ASSERT_EQ(all.size(), 2u);
  try {
    readVolume(dir);
    ADD_FAILURE() << "a folder with two series must not pick one silently";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("choose one"), std::string::npos) << e.what();
  }
  ReadOptions byNumber;
  byNumber.series = "7";
  EXPECT_EQ(readVolume(dir, byNumber).metadata().modality, "MR");
  ReadOptions byDescription;
  byDescription.series = "cranium";
  const Volume ct = readVolume(dir, byDescription);
  EXPECT_EQ(ct.metadata().modality, "CT");
  ReadOptions byUid;
  byUid.series = ct.metadata().seriesInstanceUid;
  EXPECT_EQ(readVolume(dir, byUid).dimensions(), glm::ivec3(256, 256, 108));
  ReadOptions none;
  none.series = "no such series";
  EXPECT_THROW(readVolume(dir, none), InputError);
}

}  // namespace
}  // namespace mvw::io

namespace mvw::io {
namespace {

TEST(SampleData, RtDoseFramesBecomeSlicesInGray) {
  // pydicom's rtdose.dcm: 15 frames placed by GridFrameOffsetVector (5 mm apart), uint32
  // scaled by DoseGridScaling 1e-6.
  const Volume dose = readVolume(test::sampleData("pydicom/test_files/rtdose.dcm"));
  EXPECT_EQ(dose.dimensions(), glm::ivec3(10, 10, 15));
  EXPECT_EQ(dose.components(), 1);
  EXPECT_NEAR(dose.spacing().z, 5.0, 1e-6);
  const auto [lo, hi] = dose.valueRange();
  EXPECT_NEAR(lo, 0.795, 1e-6);
  EXPECT_NEAR(hi, 1.254, 1e-6);
}

TEST(SampleData, CompressedAndBigEndianDicomDecodeToTheSameImage) {
  // The same MR slice stored uncompressed, big-endian, RLE, JPEG-LS and JPEG 2000 lossless.
  const Volume ref = readVolume(test::sampleData("pydicom/test_files/MR_small.dcm"));
  for (const char* name :
       {"MR_small_bigendian.dcm", "MR_small_RLE.dcm", "MR_small_jpeg_ls_lossless.dcm",
        "MR_small_jp2klossless.dcm", "MR_small_implicit.dcm"}) {
    const Volume v = readVolume(test::sampleData(std::string("pydicom/test_files/") + name));
    ASSERT_EQ(v.dimensions(), ref.dimensions()) << name;
    for (int j = 0; j < ref.dimensions().y; ++j)
      for (int i = 0; i < ref.dimensions().x; ++i)
        ASSERT_EQ(v.value(i, j, 0), ref.value(i, j, 0)) << name << " at " << i << "," << j;
  }
}

}  // namespace
}  // namespace mvw::io
