// The colour maps (io ColorPalettes, core ColorMap) without GL: the DICOM standard palettes
// against the standard's own tabulated values, hot metal from the renderer's preset, the names.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Error.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/study/ViewPlan.h"

namespace mvw {
namespace {

struct Entry {
  int index;
  std::array<int, 3> rgb;
};

// The standard's values (PS3.6 Annex B, the well-known Color Palette instances
// 1.2.840.10008.1.5.1-4, whose LUT data is tabulated, not segmented), read with pydicom 2.3's
// copies of those instances (apply_color_lut(palette=...)).
void expectEntries(ColorMap map, const std::vector<Entry>& entries, int tolerance) {
  const ColorTable t = io::standardColorTable(map);
  EXPECT_EQ(t.map, map);
  for (const Entry& e : entries)
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_NEAR(t.rgb[static_cast<std::size_t>(e.index)][c], e.rgb[c], tolerance)
          << toString(map) << " entry " << e.index << " channel " << c;
}

TEST(ColorPalettes, HotIronIsTheStandardsTable) {
  expectEntries(ColorMap::HotIron,
                {{0, {0, 0, 0}},
                 {32, {64, 0, 0}},
                 {64, {128, 0, 0}},
                 {100, {200, 0, 0}},
                 {128, {255, 0, 0}},
                 {160, {255, 64, 0}},
                 {192, {255, 128, 4}},
                 {224, {255, 192, 132}},
                 {255, {255, 255, 255}}},
                0);
}

TEST(ColorPalettes, PetIsTheStandardsTable) {
  expectEntries(ColorMap::Pet,
                {{0, {0, 0, 0}},
                 {32, {0, 65, 63}},
                 {64, {1, 126, 127}},
                 {100, {73, 55, 199}},
                 {128, {128, 0, 255}},
                 {160, {191, 64, 128}},
                 {192, {255, 128, 0}},
                 {224, {255, 192, 129}},
                 {255, {255, 255, 255}}},
                0);
}

// vtk-dicom builds Hot Metal Blue from the palette's ramps; its rounding differs from the
// tabulated instance by at most 2 of 255 (130 of 768 values; measured against pydicom's copy).
TEST(ColorPalettes, HotMetalBlueIsTheStandardsTableWithinTwoLevels) {
  expectEntries(ColorMap::HotMetalBlue,
                {{0, {0, 0, 0}},
                 {32, {0, 0, 63}},
                 {64, {0, 0, 125}},
                 {100, {44, 0, 196}},
                 {128, {116, 17, 97}},
                 {160, {217, 77, 0}},
                 {192, {255, 137, 65}},
                 {224, {255, 198, 159}},
                 {255, {255, 255, 255}}},
                2);
}

TEST(ColorPalettes, Pet20StepIsTheStandardsTable) {
  expectEntries(ColorMap::Pet20Step,
                {{0, {0, 0, 0}},
                 {32, {48, 48, 80}},
                 {64, {96, 96, 176}},
                 {100, {128, 128, 224}},
                 {128, {80, 192, 80}},
                 {160, {224, 224, 80}},
                 {192, {208, 144, 0}},
                 {224, {176, 48, 0}},
                 {255, {255, 255, 255}}},
                0);
  // Twenty steps: the table changes colour exactly 19 times.
  const ColorTable t = io::standardColorTable(ColorMap::Pet20Step);
  int changes = 0;
  for (std::size_t i = 1; i < 256; ++i) changes += t.rgb[i] != t.rgb[i - 1] ? 1 : 0;
  EXPECT_EQ(changes, 19);
}

TEST(ColorPalettes, GreyRampsAndHotMetal) {
  const ColorTable grey = io::standardColorTable(ColorMap::Grey);
  const ColorTable inverted = io::standardColorTable(ColorMap::GreyInverted);
  for (std::size_t i = 0; i < 256; ++i) {
    EXPECT_EQ(grey.rgb[i],
              (std::array<std::uint8_t, 3>{std::uint8_t(i), std::uint8_t(i), std::uint8_t(i)}));
    EXPECT_EQ(int(inverted.rgb[i][0]), 255 - int(i));
  }
  EXPECT_THROW(io::standardColorTable(ColorMap::HotMetal), Error);
  // Hot metal comes from the renderer's preset, through the study.
  const ColorTable hot = study::colorTable(ColorMap::HotMetal);
  EXPECT_EQ(hot.map, ColorMap::HotMetal);
  EXPECT_EQ(hot.rgb[0], (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_EQ(hot.rgb[255], (std::array<std::uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(study::colorTable(ColorMap::HotIron).rgb,
            io::standardColorTable(ColorMap::HotIron).rgb);
}

TEST(ColorPalettes, NamesRoundTrip) {
  const std::vector<std::string> names = colorMapNames();
  EXPECT_EQ(names, (std::vector<std::string>{"grey", "grey-inverted", "hot-iron", "pet",
                                             "hot-metal-blue", "pet-20-step", "hot-metal"}));
  for (const std::string& n : names) EXPECT_EQ(toString(*parseColorMap(n)), n);
  EXPECT_FALSE(parseColorMap("gray"));
  EXPECT_TRUE(takesImageColors(RenderMode::Mip));
  EXPECT_TRUE(takesImageColors(RenderMode::Mpr));
  EXPECT_FALSE(takesImageColors(RenderMode::Composite));
  EXPECT_FALSE(takesImageColors(RenderMode::ShellMip));
}

}  // namespace
}  // namespace mvw
