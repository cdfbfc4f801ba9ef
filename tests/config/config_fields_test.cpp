// The view config's field table: every key is read, written and read back; unknown keys and
// bad values are refused with the key's full path. (The table drives all three, so a key the
// writer dropped would fail FullySetViewSurvivesTheRoundTrip on its own field.)
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"

namespace mvw::config {
namespace {

using nlohmann::json;

// Every field away from its default.
ViewConfig fullySet() {
  ViewConfig v;
  v.name = "all";
  v.mode = RenderMode::Mpr;  // a mode that takes a colormap
  v.view = ViewName::Sagittal;
  v.azimuth = 12.5;
  v.elevation = -3;
  v.roll = 4;
  v.zoom = 1.7;
  v.pan = {12.5, -3.0};
  v.perspective = true;
  v.width = 300;
  v.height = 200;
  v.preset = "ct-skin";
  v.gradientOpacity = {5, 40};
  v.glyphs.on = true;
  v.glyphs.method = GlyphMethod::Simple;
  v.glyphs.convexity = GlyphConvexity::Both;
  v.glyphPlacement = GlyphPlacement::Paper;
  v.glyphSpacingMm = 7;
  v.glyphs.minSize = 0.5;
  v.glyphs.dvrOpacity = 0.5;
  v.glyphDiameterMm = 9;
  v.glyphCount = 20;
  v.glyphMapSize = 96;
  v.glyphMapDiameter = 20;
  v.glyphSeed = 3;
  v.glyphs.onSurface = true;
  v.glyphs.classKinds = {GlyphKind::Rings, GlyphKind::Crosses};
  v.functionalWindow = {0.3, 1.5};
  v.functionalClasses = 4;
  v.window = {900, 100};
  v.iso = 250;
  v.depthCue.on = true;
  v.depthCue.brightness = 0.1;
  v.depthCue.amount = 0.66;
  v.depthCue.contrast = 0.33;
  v.shells = 16;
  v.shellsDisabled = {1, 2};
  v.shading = false;
  v.sampling = Sampling::Nearest;
  v.stepMm = 0.3;
  v.jitter = false;
  v.seed = 9;
  v.background = {0.1, 0.2, 0.3};
  v.crop.min = {0, 0.1, 0.2};
  v.crop.max = {1, 0.9, 0.55};
  v.crop.minMm = glm::dvec3(-50, -60, -10);
  v.crop.maxMm = glm::dvec3(50, 40, 30.5);
  v.cutFace = CutFace::Plain;
  v.annotate = false;
  v.light = {-0.8, 0.8};
  v.planeOffsetMm = 20;
  v.slabMm = 5;
  v.overlay.mpr = false;
  v.segmentationOutlines = false;
  v.overlay.fusion = true;
  v.overlay.projection = FusionProjection::Mean;
  v.overlay.opacity = 0.7;
  v.overlay.threshold = 0.1;
  v.colormap = ColorMap::HotIron;
  v.overlayColormap = ColorMap::Pet20Step;
  v.orbit = {24, OrbitMode::Rock, 45, 20};
  return v;
}

TEST(ConfigFields, FullySetViewSurvivesTheRoundTrip) {
  const ViewConfig a = fullySet();
  const ViewConfig b = parseViewConfig(viewConfigJson(a), "study.json", "view", 0);
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.mode, a.mode);
  EXPECT_EQ(b.view, a.view);
  EXPECT_EQ(b.azimuth, a.azimuth);
  EXPECT_EQ(b.elevation, a.elevation);
  EXPECT_EQ(b.roll, a.roll);
  EXPECT_EQ(b.zoom, a.zoom);
  EXPECT_EQ(b.pan, a.pan);
  EXPECT_EQ(b.perspective, a.perspective);
  EXPECT_EQ(b.width, a.width);
  EXPECT_EQ(b.height, a.height);
  EXPECT_EQ(b.preset, a.preset);
  EXPECT_EQ(b.gradientOpacity, a.gradientOpacity);
  EXPECT_EQ(b.glyphs, a.glyphs);
  EXPECT_EQ(b.glyphPlacement, a.glyphPlacement);
  EXPECT_EQ(b.glyphSpacingMm, a.glyphSpacingMm);
  EXPECT_EQ(b.glyphDiameterMm, a.glyphDiameterMm);
  EXPECT_EQ(b.glyphCount, a.glyphCount);
  EXPECT_EQ(b.glyphMapSize, a.glyphMapSize);
  EXPECT_EQ(b.glyphMapDiameter, a.glyphMapDiameter);
  EXPECT_EQ(b.glyphSeed, a.glyphSeed);
  EXPECT_EQ(b.functionalWindow, a.functionalWindow);
  EXPECT_EQ(b.functionalClasses, a.functionalClasses);
  EXPECT_EQ(b.window, a.window);
  EXPECT_EQ(b.iso, a.iso);
  EXPECT_EQ(b.depthCue.on, a.depthCue.on);
  EXPECT_EQ(b.depthCue.brightness, a.depthCue.brightness);
  EXPECT_EQ(b.depthCue.amount, a.depthCue.amount);
  EXPECT_EQ(b.depthCue.contrast, a.depthCue.contrast);
  EXPECT_EQ(b.shells, a.shells);
  EXPECT_EQ(b.shellsDisabled, a.shellsDisabled);
  EXPECT_EQ(b.shading, a.shading);
  EXPECT_EQ(b.sampling, a.sampling);
  EXPECT_EQ(b.stepMm, a.stepMm);
  EXPECT_EQ(b.jitter, a.jitter);
  EXPECT_EQ(b.seed, a.seed);
  EXPECT_EQ(b.background, a.background);
  EXPECT_EQ(b.crop.min, a.crop.min);
  EXPECT_EQ(b.crop.max, a.crop.max);
  EXPECT_EQ(b.crop.minMm, a.crop.minMm);
  EXPECT_EQ(b.crop.maxMm, a.crop.maxMm);
  EXPECT_EQ(b.annotate, a.annotate);
  EXPECT_EQ(b.light, a.light);
  EXPECT_EQ(b.planeOffsetMm, a.planeOffsetMm);
  EXPECT_EQ(b.slabMm, a.slabMm);
  EXPECT_EQ(b.overlay.mpr, a.overlay.mpr);
  EXPECT_EQ(b.segmentationOutlines, a.segmentationOutlines);
  EXPECT_EQ(b.overlay.fusion, a.overlay.fusion);
  EXPECT_EQ(b.overlay.projection, a.overlay.projection);
  EXPECT_EQ(b.cutFace, a.cutFace);
  EXPECT_EQ(b.overlay.opacity, a.overlay.opacity);
  EXPECT_EQ(b.overlay.threshold, a.overlay.threshold);
  EXPECT_EQ(b.colormap, a.colormap);
  EXPECT_EQ(b.overlayColormap, a.overlayColormap);
  EXPECT_EQ(b.orbit, a.orbit);
}

// From the table itself, so a key added later is covered without touching this test: the fully
// set view writes every key, each (and each key of a section) away from its default, and what
// is written reads back to the same JSON. A new key fails here until fullySet() sets it.
TEST(ConfigFields, EveryKeyOfTheTableIsWrittenAwayFromItsDefaultAndReadBack) {
  const json full = viewConfigJson(fullySet());
  // The defaults, with the sections switched on so their keys are written too.
  const json defaults = viewConfigJson(parseViewConfig(
      {{"glyphs", json::object()}, {"depth_cue", json::object()}}, "study.json", "view", 0));
  for (const std::string& key : viewConfigKeys()) {
    ASSERT_TRUE(full.contains(key)) << key << " is not written";
    if (full[key].is_object() && defaults.contains(key)) {  // a section (crop_mm is not one)
      // Optional keys (glyphs.spacing_mm, diameter_mm) are written only when set.
      for (const auto& [sub, value] : full[key].items())
        if (defaults[key].contains(sub))
          EXPECT_NE(value, defaults[key][sub]) << key << "." << sub << " left at its default";
      for (const auto& [sub, value] : defaults[key].items())
        EXPECT_TRUE(full[key].contains(sub)) << key << "." << sub << " is not written";
    } else {
      EXPECT_NE(full[key], defaults.value(key, json())) << key << " left at its default";
    }
  }
  EXPECT_EQ(full.size(), viewConfigKeys().size()) << "a key written that the table does not know";
  EXPECT_EQ(viewConfigJson(parseViewConfig(full, "study.json", "view", 0)), full);
}

// The defaults live in the struct alone: an empty view object parses to a default ViewConfig,
// and what the writer writes for it parses back to the same.
TEST(ConfigFields, AnEmptyViewHasTheStructsDefaults) {
  const ViewConfig d = parseViewConfig(json::object(), "study.json", "view", 3);
  const ViewConfig defaults;
  EXPECT_EQ(d.name, "view3");
  EXPECT_EQ(d.mode, defaults.mode);
  EXPECT_EQ(d.glyphDiameterMm, defaults.glyphDiameterMm);
  EXPECT_EQ(d.zoom, defaults.zoom);
  EXPECT_FALSE(d.window.set());
  EXPECT_FALSE(d.glyphs.on);
  EXPECT_EQ(viewConfigJson(parseViewConfig(viewConfigJson(d), "s.json", "view", 0)),
            viewConfigJson(d));
  EXPECT_FALSE(viewConfigJson(d).contains("glyphs"));  // a section is written only when on
}

std::string problemOf(const json& view) {
  try {
    parseViewConfig(view, "study.json", "render.views[0]", 0);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "study.json");
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << view.dump();
  return {};
}

TEST(ConfigFields, BadKeysAndValuesNameTheKey) {
  EXPECT_NE(problemOf({{"zoomm", 2}}).find("unknown key 'render.views[0].zoomm'"),
            std::string::npos);
  EXPECT_NE(problemOf({{"glyphs", {{"sise", 1}}}}).find("render.views[0].glyphs.sise"),
            std::string::npos);
  EXPECT_NE(problemOf({{"mode", "xray"}}).find("'render.views[0].mode' must be composite"),
            std::string::npos);
  EXPECT_NE(problemOf({{"view", "top"}}).find("sagittal"), std::string::npos);
  EXPECT_NE(problemOf({{"sampling", "cubic"}}).find("must be linear or nearest"),
            std::string::npos);
  EXPECT_NE(problemOf({{"zoom", 0}}).find("'render.views[0].zoom' = "), std::string::npos);
  EXPECT_NE(problemOf({{"width", "wide"}}).find("must be a number"), std::string::npos);
  EXPECT_NE(problemOf({{"width", 48.5}}).find("48.5 must be a whole number"), std::string::npos);
  EXPECT_NE(problemOf({{"seed", 1.5}}).find("whole number"), std::string::npos);
  // Numbers in messages as %g: not "0.000000" for 1e-300, nor 300 digits for 1e300.
  EXPECT_NE(
      problemOf({{"window", 1e-300}, {"level", 0}}).find("= 1e-300 is outside 1e-09 .. 1e+12"),
      std::string::npos);
  EXPECT_NE(problemOf({{"azimuth", 1e300}}).find("= 1e+300 is outside -3600 .. 3600"),
            std::string::npos);
  EXPECT_NE(problemOf({{"window", 100}}).find("go together"), std::string::npos);
  EXPECT_NE(problemOf({{"crop_min", {0, 0, 0.5}}, {"crop_max", {1, 1, 0.5}}}).find("below"),
            std::string::npos);
  EXPECT_NE(problemOf({{"shells", 4}, {"shells_disabled", {5}}}).find("1..4"), std::string::npos);
  EXPECT_NE(problemOf({{"functional_window", {2, 1}}}).find("low < high"), std::string::npos);
  EXPECT_NE(problemOf({{"glyphs", {{"convexity", "flat"}}}}).find("convex, concave or both"),
            std::string::npos);
  EXPECT_NE(problemOf({{"name", "a/b"}}).find("plain file name"), std::string::npos);
  EXPECT_NE(problemOf(json::array()).find("must be an object"), std::string::npos);
}

TEST(ConfigFields, EnumNamesRoundTrip) {
  for (const char* n : {"anterior", "posterior", "left", "right", "superior", "inferior", "axial",
                        "coronal", "sagittal"}) {
    const auto v = parseViewName(n);
    ASSERT_TRUE(v.has_value()) << n;
    EXPECT_EQ(toString(*v), n);
  }
  EXPECT_FALSE(parseViewName("top").has_value());
  EXPECT_EQ(toString(GlyphConvexity::Dimples), "concave");
  EXPECT_EQ(toString(RegistrationMethod::Affine), "affine");
  EXPECT_EQ(parseSampling("nearest"), Sampling::Nearest);
}

// viewNumberRange gives the range the table itself enforces: the value at each end is read,
// and one just beyond is refused (mvw render's overrides are checked against these ranges).
TEST(ConfigFields, ViewNumberRangeIsTheTablesOwn) {
  for (const std::string key : {"azimuth", "elevation", "roll", "zoom", "window", "level", "iso",
                                "depth_cue.brightness", "depth_cue.amount", "depth_cue.contrast"}) {
    const auto [lo, hi] = viewNumberRange(key);
    ASSERT_LT(lo, hi) << key;
    auto view = [&](double x) {
      json v = json::object();
      const auto dot = key.find('.');
      if (dot == std::string::npos)
        v[key] = x;
      else
        v[key.substr(0, dot)][key.substr(dot + 1)] = x;
      if (key == "window") v["level"] = 0;  // window and level go together
      if (key == "level") v["window"] = 100;
      return v;
    };
    for (double x : {lo, hi})
      EXPECT_NO_THROW(parseViewConfig(view(x), "study.json", "view", 0)) << key << " " << x;
    for (double x :
         {lo - 1e-6 * std::max(1.0, std::abs(lo)), hi + 1e-6 * std::max(1.0, std::abs(hi))})
      EXPECT_THROW(parseViewConfig(view(x), "study.json", "view", 0), InputError)
          << key << " " << x;
  }
}

// A key twice in one object is refused with its path; the same key in sibling objects is not.
TEST(ConfigFields, ParseJsonRefusesDuplicateKeys) {
  auto parse = [](const std::string& text) {
    std::istringstream in(text);
    return parseJson(in, "study.json");
  };
  EXPECT_NO_THROW(parse(R"({"views": [{"width": 1}, {"width": 2}], "width": 3})"));
  try {
    parse(R"({"render": {"views": [{"width": 64, "width": 512}]}})");
    ADD_FAILURE() << "a duplicate key was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'render.views.width' appears twice"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse(R"({"a": 1, "a": 1})"), InputError);
  EXPECT_THROW(parse(R"({"a": )"), nlohmann::json::parse_error);
}

}  // namespace
}  // namespace mvw::config
