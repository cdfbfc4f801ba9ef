// Colour maps and rotating views without GL: the DICOM standard palettes against the
// standard's own tabulated values, the names, the config keys (round trip, bad values naming
// the key), the orbit's azimuths, and the movie writer (frames, size, atomic output).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Error.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/io/MovieWriter.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/TransferFunction.h"
#include "mvw/study/ViewPlan.h"

namespace mvw {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

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

std::string problemOf(const json& view) {
  try {
    config::parseViewConfig(view, "study.json", "render.views[0]", 0);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "study.json");
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << view.dump();
  return {};
}

TEST(ColorMapConfig, KeysRoundTripAndBadValuesNameTheKey) {
  const config::ViewConfig v = config::parseViewConfig({{"mode", "mip"},
                                                        {"colormap", "grey-inverted"},
                                                        {"overlay_colormap", "pet-20-step"},
                                                        {"orbit", 36},
                                                        {"orbit_mode", "rock"},
                                                        {"orbit_range", 45},
                                                        {"orbit_fps", 15}},
                                                       "study.json", "render.views[0]", 0);
  EXPECT_EQ(v.colormap, ColorMap::GreyInverted);
  EXPECT_EQ(v.overlayColormap, ColorMap::Pet20Step);
  EXPECT_EQ(v.orbit, 36);
  EXPECT_EQ(v.orbitMode, config::OrbitMode::Rock);
  EXPECT_EQ(v.orbitRangeDeg, 45);
  EXPECT_EQ(v.orbitFps, 15);
  const json written = config::viewConfigJson(v);
  EXPECT_EQ(written["colormap"], "grey-inverted");
  EXPECT_EQ(written["orbit"], 36);
  EXPECT_EQ(config::viewConfigJson(config::parseViewConfig(written, "s.json", "v", 0)), written);
  // A still writes no orbit.
  EXPECT_FALSE(config::viewConfigJson(config::ViewConfig{}).contains("orbit"));

  EXPECT_NE(problemOf({{"mode", "mip"}, {"colormap", "rainbow"}})
                .find("'render.views[0].colormap' must be grey, grey-inverted, hot-iron"),
            std::string::npos);
  EXPECT_NE(problemOf({{"overlay_colormap", 3}}).find("'render.views[0].overlay_colormap'"),
            std::string::npos);
  EXPECT_NE(problemOf({{"colormap", "hot-iron"}}).find("'render.views[0].colormap' applies to mip"),
            std::string::npos);  // the default mode is composite
  for (const json& bad : {json(0), json(1), json(-5), json(721), json(1e9), json(2.5), json("10")})
    EXPECT_NE(problemOf({{"orbit", bad}}).find("'render.views[0].orbit' must be a whole number"),
              std::string::npos)
        << bad.dump();
  EXPECT_NE(problemOf({{"orbit", 8}, {"orbit_mode", "wobble"}}).find("must be spin or rock"),
            std::string::npos);
  EXPECT_NE(problemOf({{"orbit", 8}, {"orbit_range", 0}}).find("'render.views[0].orbit_range'"),
            std::string::npos);
  EXPECT_NE(problemOf({{"orbit", 8}, {"view", "superior"}}).find("long axis"), std::string::npos);
}

TEST(Orbit, SpinTurnsAFullCircleAndRockSwingsOverItsRange) {
  config::ViewConfig v;
  v.azimuth = 10;
  v.orbit = 8;
  const std::vector<double> spin = config::orbitAzimuths(v);
  ASSERT_EQ(spin.size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_DOUBLE_EQ(spin[k], 10 + 45.0 * k);
  v.orbitMode = config::OrbitMode::Rock;
  v.orbitRangeDeg = 30;
  const std::vector<double> rock = config::orbitAzimuths(v);
  ASSERT_EQ(rock.size(), 8u);
  EXPECT_DOUBLE_EQ(rock[0], 10);
  EXPECT_NEAR(rock[2], 40, 1e-9);   // a quarter period: +range
  EXPECT_NEAR(rock[4], 10, 1e-9);   // half: back through the start
  EXPECT_NEAR(rock[6], -20, 1e-9);  // three quarters: -range
  EXPECT_NEAR(rock[1], 10 + 30 * std::sqrt(0.5), 1e-9);
  v.orbit = 0;
  EXPECT_TRUE(config::orbitAzimuths(v).empty());
}

TEST(Orbit, OverridesAreCheckedBeforeAnyWork) {
  config::StudyConfig study;
  study.file = "study.json";
  config::ViewConfig mip;
  mip.name = "mip";
  mip.mode = RenderMode::Mip;
  config::ViewConfig dvr;
  dvr.name = "dvr";
  study.render.views = {mip, dvr};
  study::ViewOverrides o;
  o.colormap = "hot-iron";
  o.orbit = 12;
  const auto views = study::planViews(study, o);
  ASSERT_EQ(views.size(), 2u);
  // --colormap reaches the views that take one; --orbit every view.
  ASSERT_TRUE(views[0].settings.imageColors);
  EXPECT_EQ(views[0].settings.imageColors->map, ColorMap::HotIron);
  EXPECT_FALSE(views[1].settings.imageColors);
  EXPECT_EQ(views[0].config.orbit, 12);
  EXPECT_EQ(views[1].config.orbit, 12);
  // Defaults: no tables, so the renderer draws exactly what it drew before colour maps.
  const auto plain = study::planViews(study, {});
  EXPECT_FALSE(plain[0].settings.imageColors);
  EXPECT_FALSE(plain[0].settings.overlayColors);
  // The inverse keeps the maps.
  o.overlayColormap = "pet";
  const auto coloured = study::planViews(study, o);
  const config::ViewConfig back = study::describeView(coloured[0].settings, "mip", "");
  EXPECT_EQ(back.colormap, ColorMap::HotIron);
  EXPECT_EQ(back.overlayColormap, ColorMap::Pet);

  auto problem = [&](const study::ViewOverrides& bad) {
    try {
      study::planViews(study, bad);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "study.json");
      return std::string(e.problem());
    }
    return std::string("no error");
  };
  for (int n : {0, 1, -3, 721, 1000000}) {
    study::ViewOverrides bad;
    bad.orbit = n;
    EXPECT_NE(problem(bad).find("--orbit must be 2..720"), std::string::npos) << n;
  }
  study::ViewOverrides badMap;
  badMap.colormap = "jet";
  EXPECT_NE(problem(badMap).find("--colormap 'jet' is not a colour map"), std::string::npos);
  config::StudyConfig dvrOnly = study;
  dvrOnly.render.views = {dvr};
  study::ViewOverrides colours;
  colours.colormap = "pet";
  try {
    study::planViews(dvrOnly, colours);
    ADD_FAILURE() << "--colormap on a study without projections";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.problem()).find("--colormap colours mip, minip, average and mpr"),
              std::string::npos);
  }
  study::ViewOverrides badMode;
  badMode.orbitMode = "tumble";
  EXPECT_NE(problem(badMode).find("--orbit-mode"), std::string::npos);
  study::ViewOverrides along;
  along.orbit = 8;
  along.view = "axial";
  EXPECT_NE(problem(along).find("every view of the study looks along it"), std::string::npos);
  // With a view along the axis among others, --orbit turns the others only.
  config::ViewConfig axial;
  axial.name = "axial";
  axial.mode = RenderMode::Mpr;
  axial.view = config::ViewName::Axial;
  study.render.views.push_back(axial);
  study::ViewOverrides some;
  some.orbit = 6;
  const auto mixed = study::planViews(study, some);
  EXPECT_EQ(mixed[0].config.orbit, 6);
  EXPECT_EQ(mixed[2].config.orbit, 0);
}

Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  return img;
}

TEST(MovieWriter, WritesEveryFrameAtAnEvenSizeAndAppearsWhole) {
  const fs::path dir = test::scratchDir();
  for (const char* name : {"spin.mp4", "spin.avi"}) {
    const fs::path path = dir / name;
    {
      io::MovieWriter movie(path, 161, 121, 10.0);  // odd: padded to 162 x 122
      for (int k = 0; k < 13; ++k)
        movie.add(solid(161, 121, std::uint8_t(20 * k), 128, std::uint8_t(255 - 20 * k)));
      EXPECT_FALSE(fs::exists(path)) << "visible before finish()";
      movie.finish();
      EXPECT_EQ(movie.frames(), 13);
      EXPECT_EQ(movie.width(), 162);
      EXPECT_EQ(movie.height(), 122);
    }
    const io::MovieInfo info = io::readMovieInfo(path);
    EXPECT_EQ(info.frames, 13) << name;
    EXPECT_EQ(info.width, 162) << name;
    EXPECT_EQ(info.height, 122) << name;
  }
  {
    io::MovieWriter abandoned(dir / "abandoned.mp4", 32, 32, 10.0);
    abandoned.add(solid(32, 32, 1, 2, 3));
    EXPECT_THROW(abandoned.add(solid(16, 32, 1, 2, 3)), Error);  // a frame of another size
  }
  // Nothing left behind: not the movie, not its temporary.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path().filename() == "spin.mp4" || e.path().filename() == "spin.avi") << e.path();
  EXPECT_THROW(io::MovieWriter(dir / "spin.gif", 32, 32, 10.0), Error);
  EXPECT_THROW(io::readMovieInfo(dir / "missing.mp4"), Error);
}

}  // namespace
// The colour bar's labels (range ends and unit) on a white background, as an inverted-grey
// MIP has: every yellow text pixel has a dark pixel within 2 px (it sits on a dark box), so
// the text reads on any background.
TEST(ColourBar, LabelsReadOnAWhiteBackground) {
  for (const int width : {256, 700}) {
    Image image(width, 2 * width);
    std::fill(image.rgba.begin(), image.rgba.end(), std::uint8_t{255});
    render::drawColourBar(image, 0.0, 8.0, "SUVbw", study::colorTable(ColorMap::GreyInverted));
    auto px = [&](int x, int y) { return &image.rgba[(std::size_t(y) * image.width + x) * 4]; };
    int text = 0, bare = 0;
    for (int y = 2; y < image.height - 2; ++y)
      for (int x = 2; x < image.width - 2; ++x) {
        const std::uint8_t* p = px(x, y);
        if (!(p[0] > 200 && p[1] > 180 && p[2] < 150)) continue;  // the labels' yellow
        ++text;
        bool dark = false;
        for (int dy = -2; dy <= 2 && !dark; ++dy)
          for (int dx = -2; dx <= 2 && !dark; ++dx) {
            const std::uint8_t* q = px(x + dx, y + dy);
            dark = std::max({q[0], q[1], q[2]}) < 80;
          }
        bare += !dark;
      }
    EXPECT_GT(text, 20) << width;
    EXPECT_EQ(bare, 0) << width << ": yellow label pixels on white, with nothing dark around";
  }
}

}  // namespace mvw
