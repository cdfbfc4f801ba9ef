// The DICOM SEG's recommended display colour (io DicomSeg): CIE L*a*b* as DICOM stores it, to
// sRGB, without files. The reader on a real SEG is tests/real-data/dicom_seg_test.cpp.
#include <array>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "mvw/io/DicomSeg.h"

namespace mvw::io {
namespace {

TEST(DicomSeg, CieLabToSrgb) {
  const auto white = io::srgbFromDicomLab(65535, 32896, 32896);
  EXPECT_EQ(white, (std::array<std::uint8_t, 3>{255, 255, 255}));
  // sRGB red is L*a*b* (53.24, 80.09, 67.20) under D65.
  const auto red =
      io::srgbFromDicomLab(static_cast<std::uint16_t>(std::lround(53.24 * 655.35)),
                           static_cast<std::uint16_t>(std::lround((80.09 + 128) * 257)),
                           static_cast<std::uint16_t>(std::lround((67.20 + 128) * 257)));
  EXPECT_GE(red[0], 253);
  EXPECT_LE(red[1], 3);
  EXPECT_LE(red[2], 3);
}

}  // namespace
}  // namespace mvw::io
