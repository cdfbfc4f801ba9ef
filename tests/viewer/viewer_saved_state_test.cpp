// Saved viewer states from before load the same (issue 56): states that `mvw view` wrote
// (ViewerState::saveConfig) with the build of 2026-12-07 (commit 475a9a6), before the settings
// became one value type per concept, checked in under tests/viewer/saved-states/. They were made
// as the panel makes them: a viewer over the CT and PET of ViewerTestUtil.h, its 3D view's
// settings edited (composite with glyphs, depth cue, crop, fusion, shells and colour maps;
// average fused by its mean, crop_mm, a window, nearest sampling), then saved. Each one loads,
// plans into the same render settings (every field, dumped beside it as NAME.settings.txt by
// that build), writes back to the same view objects, and reopens in the viewer as the state it
// was. Do not write them again: they stand for states saved before.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "ViewerTestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::viewer {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path stateDir() { return fs::path(MVW_SOURCE_DIR) / "tests" / "viewer" / "saved-states"; }

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string number(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// Every field of planned render settings, one "name = value" line each, in names that do not
// follow the C++ members: the dump stays the same when a member moves into a value type.
std::string dumpSettings(const render::RenderSettings& s) {
  std::ostringstream o;
  auto line = [&](const char* name, const std::string& value) {
    o << name << " = " << value << "\n";
  };
  auto num = [&](const char* name, double x) { line(name, number(x)); };
  auto vec = [&](const char* name, std::initializer_list<double> xs) {
    std::string t;
    for (double x : xs) t += (t.empty() ? "" : " ") + number(x);
    line(name, t);
  };
  line("mode", toString(s.mode));
  vec("size", {double(s.size.x), double(s.size.y)});
  num("camera.view", double(static_cast<int>(s.camera.view)));
  vec("camera.angles", {s.camera.azimuthDeg, s.camera.elevationDeg, s.camera.rollDeg});
  num("camera.zoom", s.camera.zoom);
  vec("camera.pan", {s.camera.panMm.x, s.camera.panMm.y});
  num("camera.perspective", s.camera.perspective);
  num("camera.fov", s.camera.fovDeg);
  num("camera.fit_aspect", s.camera.fitAspect);
  line("transfer.name", s.transfer.name);
  num("transfer.relative", s.transfer.relative);
  num("transfer.points", double(s.transfer.points.size()));
  vec("gradient_opacity", {s.gradientOpacity.low, s.gradientOpacity.high});
  vec("window_level", {s.window.window, s.window.level});
  num("iso", s.iso);
  num("depth_cue", s.depthCue.on);
  vec("depth_cue.values", {s.depthCue.brightness, s.depthCue.amount, s.depthCue.contrast});
  num("shells", s.shells);
  std::string enabled;
  for (bool e : s.shellEnabled) enabled += e ? '1' : '0';
  line("shells.enabled", enabled);
  num("step_mm", s.stepMm);
  num("shading", s.shading);
  num("linear", s.linear);
  num("jitter", s.jitter);
  num("seed", s.seed);
  vec("background", {s.background.r, s.background.g, s.background.b});
  vec("iso_color", {s.isoColor.r, s.isoColor.g, s.isoColor.b, s.isoColor.a});
  vec("light", {s.light.x, s.light.y, s.light.z, s.light.w});
  vec("light_offset", {s.lightOffset.x, s.lightOffset.y});
  vec("crop.min", {s.crop.min.x, s.crop.min.y, s.crop.min.z});
  vec("crop.max", {s.crop.max.x, s.crop.max.y, s.crop.max.z});
  if (s.crop.minMm) vec("crop.min_mm", {s.crop.minMm->x, s.crop.minMm->y, s.crop.minMm->z});
  if (s.crop.maxMm) vec("crop.max_mm", {s.crop.maxMm->x, s.crop.maxMm->y, s.crop.maxMm->z});
  num("cut_face", double(static_cast<int>(s.cutFace)));
  num("plane_offset_mm", s.planeOffsetMm);
  num("slab_mm", s.slabMm);
  num("glyphs", s.glyphs.on);
  num("glyphs.size_control", s.glyphs.method == GlyphMethod::Sized);
  num("glyphs.convexity", double(static_cast<int>(s.glyphs.convexity)));
  num("glyphs.diameter_mm", s.glyphDiameterMm);
  vec("glyphs.map", {double(s.glyphMap.size), double(s.glyphMap.count), s.glyphMap.diameter,
                     double(s.glyphMap.seed), double(static_cast<int>(s.glyphMap.placement))});
  num("glyphs.min_size", s.glyphs.minSize);
  num("glyphs.dvr_opacity", s.glyphs.dvrOpacity);
  num("glyphs.layer_mm", s.glyphLayerMm);
  num("glyphs.on_surface", s.glyphs.onSurface);
  std::string labels;
  for (const render::LabelGlyph& g : s.glyphLabels)
    labels +=
        std::to_string(g.label) + ":" + std::string(glyphKindName(g.kind)) + ":" + g.name + " ";
  line("glyphs.labels", labels);
  std::string kinds;
  for (GlyphKind k : s.glyphs.classKinds) kinds += std::string(glyphKindName(k)) + " ";
  line("glyphs.class_kinds", kinds);
  vec("functional_window", {s.functionalWindow.low, s.functionalWindow.high});
  num("functional_classes", s.functionalClasses);
  num("overlay", s.overlay.mpr);
  num("fusion", s.overlay.fusion);
  num("fusion.projection", double(static_cast<int>(s.overlay.projection)));
  num("overlay.opacity", s.overlay.opacity);
  num("overlay.threshold", s.overlay.threshold);
  num("segment_outlines", s.segmentationOutlines);
  line("image_colors", s.imageColors ? toString(s.imageColors->map) : "none");
  line("overlay_colors", s.overlayColors ? toString(s.overlayColors->map) : "none");
  return o.str();
}

// The state file as a study config whose volumes are the state file itself (the loader checks
// only that they exist; the paths of the machine that saved it are not this one's).
config::StudyConfig loadState(const fs::path& file) {
  std::ifstream in(file);
  json j = config::parseJson(in, file);
  j["anatomical"]["path"] = file.filename().string();
  if (j.contains("functional")) j["functional"]["path"] = file.filename().string();
  return config::studyConfigFromJson(j, file);
}

class ViewerSavedStateTest : public ViewerFixture,
                             public ::testing::WithParamInterface<const char*> {};

TEST_P(ViewerSavedStateTest, PlansTheSameSettings) {
  const fs::path file = stateDir() / (std::string(GetParam()) + ".json");
  const config::StudyConfig loaded = loadState(file);
  std::string dump;
  for (const mvw::study::PlannedView& v : mvw::study::planViews(loaded, {}))
    dump += "[" + v.config.name + "]\n" + dumpSettings(v.settings);
  EXPECT_EQ(dump, readText(stateDir() / (std::string(GetParam()) + ".settings.txt")));
}

TEST_P(ViewerSavedStateTest, WritesTheSameViews) {
  const fs::path file = stateDir() / (std::string(GetParam()) + ".json");
  std::ifstream in(file);
  const json saved = config::parseJson(in, file);
  const config::StudyConfig loaded = loadState(file);
  ASSERT_EQ(loaded.render.views.size(), saved["render"]["views"].size());
  for (std::size_t i = 0; i < loaded.render.views.size(); ++i)
    EXPECT_EQ(config::viewConfigJson(loaded.render.views[i]), saved["render"]["views"][i]) << i;
}

TEST_P(ViewerSavedStateTest, ReopensAsTheSameState) {
  const fs::path file = stateDir() / (std::string(GetParam()) + ".json");
  std::ifstream in(file);
  const json saved = config::parseJson(in, file);
  const config::StudyConfig loaded = loadState(file);  // the state holds it by reference
  ViewerState state(loaded, ct, &pet, sceneOf(ct));
  renderAll(state);
  const fs::path again = test::scratchDir() / "again.json";
  state.saveConfig(again);
  std::ifstream in2(again);
  const json resaved = config::parseJson(in2, again);
  EXPECT_EQ(resaved["render"], saved["render"]);
  EXPECT_EQ(resaved["layout"], saved["layout"]);
}

INSTANTIATE_TEST_SUITE_P(States, ViewerSavedStateTest,
                         ::testing::Values("composite-glyphs", "average-fused"));

}  // namespace
}  // namespace mvw::viewer
