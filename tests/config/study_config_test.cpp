#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Frame.h"

namespace mvw::config {
namespace {

namespace fs = std::filesystem;

fs::path writeConfig(const fs::path& dir, const std::string& text) {
  std::ofstream(dir / "anat.nii") << "x";
  std::ofstream(dir / "pet.nii") << "x";
  const fs::path p = dir / "study.json";
  std::ofstream(p) << text;
  return p;
}

std::string errorOf(const fs::path& p) {
  try {
    loadStudyConfig(p);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p);
    return e.problem();
  }
  ADD_FAILURE() << "no InputError for " << p;
  return {};
}

TEST(StudyConfig, ResolvesPathsRelativeToTheConfig) {
  const fs::path dir = test::scratchDir();
  const auto p = writeConfig(dir, R"({"name": "x", "anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "pet", "series": "3"}})");
  const StudyConfig c = loadStudyConfig(p);
  EXPECT_EQ(c.name, "x");
  EXPECT_EQ(c.anatomical.path, dir / "anat.nii");
  ASSERT_TRUE(c.functional.has_value());
  EXPECT_EQ(c.functional->series, "3");
  EXPECT_EQ(c.functionalKind, FunctionalKind::Pet);
}

TEST(StudyConfig, SliceSpacingForResampledDicomSeries) {
  const fs::path dir = test::scratchDir();
  const auto p =
      writeConfig(dir, R"({"anatomical": {"path": "anat.nii", "slice_spacing_mm": 1.5}})");
  EXPECT_EQ(loadStudyConfig(p).anatomical.sliceSpacingMm, 1.5);
  EXPECT_NE(
      errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii", "slice_spacing_mm": -1}})"))
          .find("anatomical.slice_spacing_mm"),
      std::string::npos);
}

TEST(StudyConfig, RefusesTyposMissingKeysAndBadValues) {
  const fs::path dir = test::scratchDir();
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"}, "fucntional": {}})"))
                .find("unknown key 'fucntional'"),
            std::string::npos);
  EXPECT_NE(
      errorOf(writeConfig(dir, R"({"anatomical": {"pth": "anat.nii"}})")).find("anatomical.pth"),
      std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"name": "x"})")).find("missing key 'anatomical'"),
            std::string::npos);
  EXPECT_NE(
      errorOf(writeConfig(dir, R"({"anatomical": {"path": "nope.nii"}})")).find("does not exist"),
      std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": 3}})")).find("must be a string"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "xray"}})"))
                .find("functional.kind"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": )")).find("not valid JSON"),
            std::string::npos);
  // Glyph placement keys (issue 15).
  std::ofstream(dir / "a.nii") << "x";
  const std::string glyphView =
      R"({"anatomical": {"path": "a.nii"}, "render": {"views": [{"glyphs": )";
  EXPECT_NE(errorOf(writeConfig(dir, glyphView + R"({"placement": "poisson"}}]}})"))
                .find("glyphs.placement"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, glyphView + R"({"min_size": 2}}]}})")).find("glyphs.min_size"),
            std::string::npos);
  EXPECT_NE(
      errorOf(writeConfig(dir, glyphView + R"({"spacing_mm": 0}}]}})")).find("glyphs.spacing_mm"),
      std::string::npos);
}

// The config leaves a glyph spacing or diameter it was not given open (study::planViews and
// applyGlyphScale choose them: see study_test), and keeps what it was given.
TEST(StudyConfig, GlyphSpacingAndDiameterStayOpenUnlessGiven) {
  const fs::path dir = test::scratchDir();
  std::ofstream(dir / "a.nii") << "x";
  const StudyConfig c = loadStudyConfig(writeConfig(dir, R"({"anatomical": {"path": "a.nii"},
      "render": {"views": [{"glyphs": {}}, {"glyphs": {"spacing_mm": 8, "diameter_mm": 5}}]}})"));
  ASSERT_EQ(c.render.views.size(), 2u);
  EXPECT_FALSE(c.render.views[0].glyphSpacingMm.has_value());
  EXPECT_FALSE(c.render.views[0].glyphDiameterMm.has_value());
  EXPECT_EQ(c.render.views[1].glyphSpacingMm, 8.0);
  EXPECT_EQ(c.render.views[1].glyphDiameterMm, 5.0);
}

// writeStudyConfig is loadStudyConfig's inverse: every field survives the round trip (the
// viewer saves its state this way, and `mvw render` must reproduce it).
// "frame" of a source (issue 14 item 8) and "crop_mm" of a view (item 3): parsed, defaulted,
// refused with the key's path, and written back.
TEST(StudyConfig, FrameChoosesWhatA4DVolumeGivesAndCropMmIsABoxInLpsMm) {
  const fs::path dir = test::scratchDir();
  StudyConfig c = loadStudyConfig(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "fmri"}})"));
  EXPECT_FALSE(c.anatomical.frame.has_value());  // the anatomy: frame 0 (StudyLoader)
  ASSERT_TRUE(c.functional->frame.has_value());
  EXPECT_TRUE(c.functional->frame->mean);  // a time series: the mean by default
  c = loadStudyConfig(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "functional": {"path": "pet.nii", "kind": "labels"}})"));
  EXPECT_FALSE(c.functional->frame->mean);  // labels: frame 0
  EXPECT_EQ(c.functional->frame->index, 0);
  c = loadStudyConfig(writeConfig(dir, R"({"anatomical": {"path": "anat.nii", "frame": 2},
      "functional": {"path": "pet.nii", "kind": "fmri", "frame": 7},
      "render": {"views": [{"crop_mm": {"min": [-50, -60, -10], "max": [50, 40, 30.5]}}]}})"));
  EXPECT_EQ(c.anatomical.frame->index, 2);
  EXPECT_EQ(c.functional->frame->index, 7);
  EXPECT_FALSE(c.functional->frame->mean);
  ASSERT_TRUE(c.render.views[0].crop.maxMm.has_value());
  EXPECT_EQ((*c.render.views[0].crop.maxMm)[2], 30.5);
  EXPECT_EQ((*c.render.views[0].crop.minMm)[1], -60);
  writeStudyConfig(c, dir / "written.json");
  const StudyConfig d = loadStudyConfig(dir / "written.json");
  EXPECT_EQ(d.functional->frame->index, 7);
  EXPECT_EQ(d.render.views[0].crop.maxMm, c.render.views[0].crop.maxMm);
  for (const char* bad : {R"("frame": -1)", R"("frame": "last")", R"("frame": 1.5)",
                          R"("frame": "3")", R"("frame": true)"}) {
    const std::string text = std::string(R"({"anatomical": {"path": "anat.nii"},
        "functional": {"path": "pet.nii", )") +
                             bad + "}}";
    EXPECT_NE(errorOf(writeConfig(dir, text)).find("'functional.frame' must be a frame number"),
              std::string::npos)
        << bad;
  }
  for (const char* bad : {R"({"min": [0, 0, 0]})", R"({"min": [0, 0, 0], "max": [1, 1]})",
                          R"({"min": [0, 0, 5], "max": [1, 1, 1]})", R"([0, 1])",
                          R"({"min": [0, 0, 0], "max": [1, 1, 1], "mid": [0, 0, 0]})"}) {
    const std::string text =
        std::string(R"({"anatomical": {"path": "anat.nii"}, "render": {"views": [{"crop_mm": )") +
        bad + "}]}}";
    EXPECT_NE(errorOf(writeConfig(dir, text)).find("'render.views[0].crop_mm' must be"),
              std::string::npos)
        << bad;
  }
}

// "measurements" (the viewer's sphere ROIs and rulers, LPS mm): read, written back the same,
// not written when there are none, and refused with the key's path when malformed.
TEST(StudyConfig, MeasurementsRoundTripAndBadOnesNameTheKey) {
  const fs::path dir = test::scratchDir();
  const StudyConfig c = loadStudyConfig(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "measurements": {"spheres": [[1.5, -20, 300.25, 12], [0, 0, 0, 3]],
                       "rulers": [[0, 0, 0, 30, 40, 0]]}})"));
  ASSERT_EQ(c.measurements.spheres.size(), 2u);
  EXPECT_EQ(c.measurements.spheres[0].centre, (std::array<double, 3>{1.5, -20, 300.25}));
  EXPECT_EQ(c.measurements.spheres[0].radiusMm, 12);
  ASSERT_EQ(c.measurements.rulers.size(), 1u);
  EXPECT_EQ(c.measurements.rulers[0].to, (std::array<double, 3>{30, 40, 0}));
  writeStudyConfig(c, dir / "written.json");
  EXPECT_EQ(loadStudyConfig(dir / "written.json").measurements, c.measurements);
  StudyConfig none = c;
  none.measurements = {};
  writeStudyConfig(none, dir / "none.json");
  std::ifstream in(dir / "none.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}).find("measurements"),
            std::string::npos);
  for (const char* bad : {R"({"spheres": [[0, 0, 0]]})", R"({"spheres": [[0, 0, 0, 0]]})",
                          R"({"spheres": [[0, 0, "x", 2]]})", R"({"spheres": [[0, 0, 1e9, 2]]})"})
    EXPECT_NE(errorOf(writeConfig(dir, std::string(R"({"anatomical": {"path": "anat.nii"},
        "measurements": )") + bad + "}"))
                  .find("'measurements.spheres[0]' must be [L, P, S, radius]"),
              std::string::npos)
        << bad;
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "measurements": {"rulers": [[0, 0, 0, 1, 1]]}})"))
                .find("'measurements.rulers[0]' must be [L0, P0, S0, L1, P1, S1]"),
            std::string::npos);
  EXPECT_NE(errorOf(writeConfig(dir, R"({"anatomical": {"path": "anat.nii"},
      "measurements": {"circles": []}})"))
                .find("unknown key 'measurements.circles'"),
            std::string::npos);
}

TEST(StudyConfig, WrittenConfigLoadsBackTheSame) {
  const fs::path dir = test::scratchDir();
  const auto p =
      writeConfig(dir, R"({"name": "round trip", "anatomical": {"path": "anat.nii", "series": "7"},
      "functional": {"path": "pet.nii", "kind": "labels"},
      "registration": {"method": "rigid", "rotation_search_deg": 30},
      "render": {"views": [
        {"name": "a", "mode": "composite", "view": "superior", "azimuth": 12.5, "elevation": -3, "roll": 4,
         "zoom": 1.7, "perspective": true, "width": 300, "height": 200, "preset": "ct-skin",
         "gradient_opacity": [5, 40], "glyphs": {"method": "simple", "convexity": "both", "diameter_mm": 9,
         "count": 20, "seed": 3, "map_size": 96, "map_diameter": 20, "placement": "paper",
         "spacing_mm": 7, "min_size": 0.5}, "functional_window": [0.3, 1.5],
         "functional_classes": 4, "crop_min": [0, 0.1, 0], "crop_max": [1, 1, 0.55], "light": [-0.8, 0.8],
         "shading": false, "sampling": "nearest", "step_mm": 0.3, "jitter": false, "seed": 9,
         "background": [0.1, 0.2, 0.3], "annotate": false, "fusion": true, "overlay_opacity": 0.7,
         "overlay_threshold": 0.1},
        {"name": "b", "mode": "mip", "window": 1000, "level": 500,
         "depth_cue": {"brightness": 0.1, "amount": 0.66, "contrast": 0.33}},
        {"name": "c", "mode": "shells-lit", "shells": 16, "shells_disabled": [1, 2]},
        {"name": "d", "mode": "mpr", "view": "coronal", "plane_offset_mm": 20, "slab_mm": 5, "overlay": false}]}})");
  const StudyConfig c = loadStudyConfig(p);
  const fs::path written = dir / "written.json";
  writeStudyConfig(c, written);
  const StudyConfig d = loadStudyConfig(written);
  const fs::path again = dir / "again.json";
  writeStudyConfig(d, again);
  auto text = [](const fs::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(written), text(again));
  EXPECT_EQ(d.anatomical.path, dir / "anat.nii");
  EXPECT_EQ(d.anatomical.series, "7");
  EXPECT_EQ(d.functionalKind, FunctionalKind::Labels);
  EXPECT_EQ(d.registration.method, RegistrationMethod::Rigid);
  EXPECT_EQ(d.registration.rotationSearchDeg, 30.0);
  ASSERT_EQ(d.render.views.size(), 4u);
  const ViewConfig& a = d.render.views[0];
  EXPECT_TRUE(a.glyphs.on);
  EXPECT_EQ(a.glyphs.method, GlyphMethod::Simple);
  EXPECT_EQ(a.glyphs.convexity, GlyphConvexity::Both);
  EXPECT_EQ(a.glyphDiameterMm, 9.0);
  EXPECT_EQ(a.glyphCount, 20);
  EXPECT_EQ(a.glyphMapSize, 96);
  EXPECT_EQ(a.glyphPlacement, GlyphPlacement::Paper);
  EXPECT_EQ(a.glyphSpacingMm, 7.0);
  EXPECT_EQ(a.glyphs.minSize, 0.5);
  ASSERT_TRUE(a.functionalWindow.set());
  EXPECT_EQ(a.functionalWindow.high, 1.5);
  EXPECT_EQ(a.functionalClasses, 4);
  EXPECT_EQ(a.crop.max[2], 0.55);
  EXPECT_EQ(a.light[0], -0.8);
  EXPECT_FALSE(a.shading);
  EXPECT_EQ(a.sampling, Sampling::Nearest);
  EXPECT_EQ(a.background[2], 0.3);
  EXPECT_TRUE(a.perspective);
  EXPECT_EQ(a.gradientOpacity.high, 40.0);
  EXPECT_TRUE(a.overlay.fusion);
  EXPECT_EQ(a.overlay.opacity, 0.7);
  const ViewConfig& b = d.render.views[1];
  EXPECT_TRUE(b.depthCue.on);
  EXPECT_EQ(b.depthCue.amount, 0.66);
  ASSERT_TRUE(b.window.set());
  EXPECT_EQ(b.window.level, 500.0);
  EXPECT_EQ(d.render.views[2].shellsDisabled, (std::vector<int>{1, 2}));
  EXPECT_EQ(d.render.views[3].slabMm, 5.0);
  EXPECT_FALSE(d.render.views[3].overlay.mpr);
}

// Every study-level field away from its default, written, loaded back and compared field by
// field (write(load(write(c))) == write(c) cannot see a field the writer drops); then, from the
// written JSON, every key of every object differs from what a default study writes, so a new
// key that the fully set study leaves at its default fails here.
TEST(StudyConfig, FullySetStudyLoadsBackFieldByField) {
  const fs::path dir = test::scratchDir();
  writeConfig(dir, "{}");
  std::ofstream(dir / "seg.nii") << "x";
  std::ofstream(dir / "t.tfm") << "x";
  StudyConfig c;
  c.name = "every field";
  c.anatomical = {dir / "anat.nii", "7", "", "", FrameChoice{false, 2}, 1.5};
  c.functional = VolumeSource{dir / "pet.nii", "3", "", "", FrameChoice{true, 0}, 2.5};
  c.functionalKind = FunctionalKind::Dose;
  c.segmentation = VolumeSource{dir / "seg.nii", "9", "", "", FrameChoice{false, 1}, 0.5};
  c.registration = {RegistrationMethod::File, dir / "t.tfm", 20.0};
  c.measurements.spheres = {{{1.0, -2.0, 3.0}, 7.5}};
  c.measurements.rulers = {{{0.0, 0.0, 0.0}, {10.0, 0.0, 5.0}}};
  c.layout = ViewerLayout::PetCtCoronal;
  ViewConfig v;
  v.name = "only";
  v.zoom = 2.0;
  c.render.views = {v};
  const fs::path written = dir / "written.json";
  writeStudyConfig(c, written);
  const StudyConfig d = loadStudyConfig(written);
  EXPECT_EQ(d.name, c.name);
  for (const auto& [a, b] :
       {std::pair{&c.anatomical, &d.anatomical},
        std::pair{&*c.functional, d.functional ? &*d.functional : nullptr},
        std::pair{&*c.segmentation, d.segmentation ? &*d.segmentation : nullptr}}) {
    ASSERT_NE(b, nullptr) << a->path;
    EXPECT_EQ(b->path, a->path);
    EXPECT_EQ(b->series, a->series) << a->path;
    ASSERT_TRUE(b->frame.has_value()) << a->path;
    EXPECT_EQ(b->frame->mean, a->frame->mean) << a->path;
    EXPECT_EQ(b->frame->index, a->frame->index) << a->path;
    EXPECT_EQ(b->sliceSpacingMm, a->sliceSpacingMm) << a->path;
  }
  EXPECT_EQ(d.functionalKind, c.functionalKind);
  EXPECT_EQ(d.registration.method, c.registration.method);
  EXPECT_EQ(d.layout, c.layout);
  EXPECT_EQ(d.registration.transform, c.registration.transform);
  EXPECT_EQ(d.registration.rotationSearchDeg, c.registration.rotationSearchDeg);
  ASSERT_EQ(d.render.views.size(), 1u);
  EXPECT_EQ(viewConfigJson(d.render.views[0]), viewConfigJson(v));  // views: config_fields_test

  // From the written JSON: each object's keys all away from a default study's.
  StudyConfig defaults;
  defaults.anatomical.path = dir / "anat.nii";
  defaults.functional = VolumeSource{dir / "pet.nii"};
  defaults.segmentation = VolumeSource{dir / "seg.nii"};
  const fs::path writtenDefaults = dir / "defaults.json";
  writeStudyConfig(defaults, writtenDefaults);
  auto parse = [](const fs::path& f) { return nlohmann::json::parse(std::ifstream(f)); };
  const nlohmann::json full = parse(written), def = parse(writtenDefaults);
  for (const auto& [key, value] : full.items()) {
    if (key == "render") continue;  // the views: config_fields_test, from the view table
    if (!value.is_object()) {
      EXPECT_NE(value, def.value(key, nlohmann::json())) << key << " left at its default";
      continue;
    }
    for (const auto& [sub, subValue] : value.items())
      if (sub != "path")  // the same files (they must exist)
        EXPECT_NE(subValue, def.value(key, nlohmann::json::object()).value(sub, nlohmann::json()))
            << key << "." << sub << " left at its default";
  }
  for (const char* key : {"name", "anatomical", "functional", "segmentation", "registration"})
    EXPECT_TRUE(full.contains(key)) << key << " is not written";
  for (const char* key : {"series", "frame", "slice_spacing_mm"})
    for (const char* source : {"anatomical", "functional", "segmentation"})
      EXPECT_TRUE(full[source].contains(key)) << source << "." << key << " is not written";
  EXPECT_EQ(d.measurements, c.measurements);
  // From the field tables, so a key added later is covered without touching this test: every
  // key path is written, away from a default study's value (a new key fails here until the
  // fully set study above sets it).
  for (const std::string& path : studyConfigKeyPaths()) {
    if (path == "render.views") continue;  // config_fields_test, from the view table
    const auto dot = path.find('.');
    const std::string key = path.substr(0, dot);
    ASSERT_TRUE(full.contains(key)) << key << " is not written";
    if (dot == std::string::npos) continue;
    const std::string sub = path.substr(dot + 1);
    // A source names a path or a PACS series, never both: PacsSourceLoadsBack covers those.
    if (sub == "pacs" || sub == "study") continue;
    EXPECT_TRUE(full[key].contains(sub)) << path << " is not written";
    if (sub != "path" && full[key].contains(sub))
      EXPECT_NE(full[key][sub],
                def.value(key, nlohmann::json::object()).value(sub, nlohmann::json()))
          << path << " left at its default";
  }
}

// A source naming a PACS series (issue 37): "pacs", "study" and "series" written and loaded back,
// no "path"; the config refuses a path beside it, a missing study, a study that is not a UID,
// credentials in the server URL and a server that is not one.
TEST(StudyConfig, PacsSourceLoadsBack) {
  const fs::path dir = test::scratchDir();
  StudyConfig c;
  c.anatomical.pacs = "http://127.0.0.1:8042/dicom-web";
  c.anatomical.study = "1.2.840.113619.2.55";
  c.anatomical.series = "CT";
  c.functional = VolumeSource{};
  c.functional->pacs = "dicom://ORTHANC@127.0.0.1:4242";
  c.functional->study = "1.2.840.113619.2.55";
  c.functional->series = "PT";
  const fs::path written = dir / "pacs.json";
  writeStudyConfig(c, written);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(written));
  EXPECT_FALSE(j["anatomical"].contains("path")) << j.dump();
  const StudyConfig d = loadStudyConfig(written);
  EXPECT_EQ(d.anatomical.pacs, c.anatomical.pacs);
  EXPECT_EQ(d.anatomical.study, c.anatomical.study);
  EXPECT_EQ(d.anatomical.series, "CT");
  EXPECT_TRUE(d.anatomical.path.empty());
  ASSERT_TRUE(d.functional.has_value());
  EXPECT_EQ(d.functional->pacs, c.functional->pacs);
  EXPECT_EQ(d.functional->series, "PT");
  std::ofstream(dir / "ct.nii") << "x";
  for (
      const char* bad :
      {R"({"anatomical": {"path": "ct.nii", "pacs": "http://h/dw", "study": "1.2", "series": "1"}})",
       R"({"anatomical": {"pacs": "http://h/dw", "series": "1"}})",
       R"({"anatomical": {"pacs": "http://h/dw", "study": "../x", "series": "1"}})",
       R"({"anatomical": {"pacs": "http://u:pw@h/dw", "study": "1.2", "series": "1"}})",
       R"({"anatomical": {"pacs": "ftp://h", "study": "1.2", "series": "1"}})",
       R"({"anatomical": {"path": "ct.nii", "study": "1.2"}})"}) {
    writeConfig(dir, bad);
    EXPECT_THROW(loadStudyConfig(dir / "study.json"), InputError) << bad;
  }
}

}  // namespace
}  // namespace mvw::config
