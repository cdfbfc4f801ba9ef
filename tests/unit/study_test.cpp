// modules/study without GL or files: view planning and its inverse, overrides, captions,
// defaults by modality; and the study loader on the fetched nipy fMRI.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Framing.h"
#include "mvw/study/Caption.h"
#include "mvw/study/ModalityDefaults.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

config::StudyConfig studyWith(const nlohmann::json& view) {
  config::StudyConfig s;
  s.file = "study.json";
  s.anatomical.path = "ct.nii";
  s.functional = config::VolumeSource{"pet.nii", "", std::nullopt};
  s.render.views = {config::parseViewConfig(view, s.file, "view", 0)};
  return s;
}

// describeView is planViews' inverse: the config it writes plans back to the same renderer
// settings, field for field (the viewer saves its panes this way).
TEST(ViewPlan, DescribeViewIsTheInverseOfPlanViews) {
  const nlohmann::json view = {
      {"name", "a"},
      {"mode", "composite"},
      {"view", "superior"},
      {"azimuth", 12.5},
      {"elevation", -3},
      {"roll", 4},
      {"zoom", 1.7},
      {"perspective", true},
      {"width", 300},
      {"height", 200},
      {"preset", "ct-skin"},
      {"gradient_opacity", {5, 40}},
      {"functional_window", {0.3, 1.5}},
      {"functional_classes", 4},
      {"crop_min", {0, 0.1, 0}},
      {"crop_max", {1, 1, 0.55}},
      {"light", {-0.8, 0.8}},
      {"shading", false},
      {"sampling", "nearest"},
      {"step_mm", 0.3},
      {"jitter", false},
      {"seed", 9},
      {"background", {0.125, 0.25, 0.5}},  // exact in float, as the renderer holds it
      {"fusion", true},
      {"overlay_opacity", 0.75},
      {"overlay_threshold", 0.125},
      {"window", 900},
      {"level", 100},
      {"iso", 250},
      {"shells", 16},
      {"shells_disabled", {1, 2}},
      {"plane_offset_mm", 20},
      {"slab_mm", 5},
      {"overlay", false},
      {"segmentation_outlines", false},
      {"depth_cue", {{"brightness", 0.1}, {"amount", 0.66}, {"contrast", 0.33}}},
      {"glyphs",
       {{"method", "simple"},
        {"convexity", "both"},
        {"placement", "paper"},
        {"min_size", 0.5},
        {"diameter_mm", 9},
        {"count", 20},
        {"seed", 3},
        {"map_size", 96},
        {"map_diameter", 20}}}};
  const config::StudyConfig study = studyWith(view);
  const std::vector<PlannedView> planned = planViews(study);
  ASSERT_EQ(planned.size(), 1u);
  const config::ViewConfig back = describeView(planned[0].settings, "a", "ct-skin");
  EXPECT_EQ(config::viewConfigJson(back), config::viewConfigJson(study.render.views[0]));
  const std::vector<PlannedView> again = planViews(studyWith(config::viewConfigJson(back)));
  EXPECT_EQ(config::viewConfigJson(describeView(again[0].settings, "a", "ct-skin")),
            config::viewConfigJson(back));
}

TEST(ViewPlan, MprPlaneNamesAreTheirStandardViews) {
  EXPECT_EQ(standardView(config::ViewName::Axial), render::StandardView::Inferior);
  EXPECT_EQ(standardView(config::ViewName::Coronal), render::StandardView::Anterior);
  EXPECT_EQ(standardView(config::ViewName::Sagittal), render::StandardView::Left);
  for (int v = 0; v < 6; ++v) {
    const auto sv = static_cast<render::StandardView>(v);
    EXPECT_EQ(standardView(viewName(sv)), sv);
  }
}

TEST(ViewPlan, OverridesReplaceTheViewsOwnAndBadOnesAreBadInput) {
  const config::StudyConfig study = studyWith({{"mode", "composite"}});
  ViewOverrides o;
  o.mode = "mip";
  o.view = "axial";
  o.size = 64;
  const PlannedView p = planViews(study, o).at(0);
  EXPECT_EQ(p.settings.mode, RenderMode::Mip);
  EXPECT_EQ(p.settings.camera.view, render::StandardView::Inferior);
  EXPECT_EQ(p.settings.size, glm::ivec2(64, 64));
  o.mode = "xray";
  try {
    planViews(study, o);
    ADD_FAILURE() << "no InputError for --mode xray";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--mode 'xray'"), std::string::npos) << e.what();
  }
}

TEST(ViewPlan, GlyphsNeedAFunctionalVolumeAndASurfaceMode) {
  config::StudyConfig study = studyWith({{"glyphs", nlohmann::json::object()}});
  study.functional.reset();
  EXPECT_THROW(planViews(study), InputError);
  EXPECT_THROW(planViews(studyWith({{"mode", "mip"}, {"glyphs", nlohmann::json::object()}})),
               InputError);
}

TEST(Caption, SaysWhatTheViewShows) {
  PlannedView mip =
      planViews(studyWith({{"mode", "mip"}, {"depth_cue", {{"brightness", 0.1}, {"amount", 0.5}}}}))
          .at(0);
  EXPECT_EQ(viewCaption(mip, {400, 40}), "mip  W 400 L 40  depth cue b0 0.10 a 0.50 b 1.00");
  PlannedView mpr =
      planViews(studyWith({{"mode", "mpr"}, {"view", "coronal"}, {"slab_mm", 10}})).at(0);
  EXPECT_EQ(viewCaption(mpr, {2000, 500}), "mpr coronal  slab 10 mm  W 2000 L 500");
  PlannedView glyphs =
      planViews(studyWith({{"preset", "ct-skin"}, {"glyphs", {{"convexity", "concave"}}}})).at(0);
  EXPECT_EQ(viewCaption(glyphs, {}), "composite  ct-skin  glyphs sized concave");
}

Volume volumeOf(const std::string& modality, const std::string& unit) {
  Volume v({2, 2, 2}, 1, ScalarType::Int16, glm::dmat4(1.0));
  v.metadata().modality = modality;
  v.metadata().unit = unit;
  return v;
}

TEST(ModalityDefaults, CtGetsBoneAndTheSoftTissueWindowMrTheRange) {
  const ModalityDefaults ct = modalityDefaults(volumeOf("CT", "HU"), {-1024, 3071});
  EXPECT_EQ(ct.preset, "ct-bone");
  EXPECT_EQ(ct.isoValue, 300.0);
  EXPECT_EQ(ct.mpr.window, 400.0);
  EXPECT_EQ(ct.mpr.level, 40.0);
  const ModalityDefaults mr = modalityDefaults(volumeOf("MR", ""), {0, 1000});
  EXPECT_EQ(mr.preset, "mr-default");
  EXPECT_EQ(mr.isoValue, 400.0);
  EXPECT_EQ(mr.mpr.window, 1000.0);
  EXPECT_EQ(mr.mpr.level, 500.0);
  EXPECT_EQ(defaultPreset(volumeOf("PT", "SUVbw")), "pet-hot-metal");
  EXPECT_EQ(defaultPreset(volumeOf("", "HU")), "ct-bone");  // HU without a modality: a CT
}

}  // namespace
}  // namespace mvw::study

namespace mvw::study {
namespace {

TEST(AttributeDefaults, PetInSuvFromTheLesionThresholdOtherUnitsFrom41Percent) {
  const Volume suv = volumeOf("PT", "SUVbw");
  const auto a = defaultAttributeWindow(config::FunctionalKind::Pet, suv, {0.0, 19.5});
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ((*a)[0], 2.5);
  EXPECT_EQ((*a)[1], 19.5);
  // No uptake above 2.5: a valid window that shows none.
  const auto none = defaultAttributeWindow(config::FunctionalKind::Pet, suv, {0.0, 1.8});
  ASSERT_TRUE(none.has_value());
  EXPECT_EQ((*none)[0], 2.5);
  EXPECT_GT((*none)[1], 2.5);
  // Bq/ml, or a NIfTI PET without a unit: relative to the maximum.
  const auto bq = defaultAttributeWindow(config::FunctionalKind::Pet, volumeOf("", ""), {0, 4.0});
  ASSERT_TRUE(bq.has_value());
  EXPECT_DOUBLE_EQ((*bq)[0], 0.41 * 4.0);
  EXPECT_EQ((*bq)[1], 4.0);
  // The modality alone says PET too; fMRI, labels and the rest keep the full range.
  EXPECT_TRUE(defaultAttributeWindow(config::FunctionalKind::Other, volumeOf("NM", ""), {0, 9}));
  EXPECT_FALSE(defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("MR", ""), {0, 9}));
  // An fMRI statistic map (z or t from the NIfTI intent code): from z = 2.3.
  const auto z = defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("", "z"), {-4, 9});
  ASSERT_TRUE(z.has_value());
  EXPECT_EQ((*z)[0], 2.3);
  EXPECT_EQ((*z)[1], 9.0);
  EXPECT_FALSE(defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("", "t"), {-4, 2}));
  EXPECT_FALSE(defaultAttributeWindow(config::FunctionalKind::Labels, volumeOf("", ""), {0, 9}));
}

// Defaults: blue-noise glyphs 0.85 of their spacing (provisionally 5 mm until the volumes are
// known); the paper's map keeps its 6 mm.
TEST(GlyphDefaults, DiameterFollowsThePlacementAndSpacing) {
  const auto diameter = [](const nlohmann::json& glyphs) {
    return planViews(studyWith({{"glyphs", glyphs}})).at(0).settings.glyphDiameterMm;
  };
  EXPECT_DOUBLE_EQ(diameter(nlohmann::json::object()), 0.85 * 5.0);
  EXPECT_DOUBLE_EQ(diameter({{"spacing_mm", 8}}), 0.85 * 8.0);
  EXPECT_EQ(diameter({{"placement", "paper"}}), 6.0);
  EXPECT_EQ(diameter({{"spacing_mm", 8}, {"diameter_mm", 3}}), 3.0);
}

// The automatic spacing: the functional voxel, within [what the image shows, 5 mm]; the scale
// wins where a 5 mm glyph would make sub-pixel bumps (a whole-body MIP-sized field of view).
TEST(GlyphDefaults, SpacingFollowsTheFunctionalVoxelAndTheRenderedScale) {
  // The weakest bump's radius is 0.6 * 0.85 / 2 of the spacing; it must be 1.5 px.
  const double perPixel = 1.5 / (0.6 * 0.85 / 2.0);
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(4.0, 0.2, 0.6), 4.0);             // PET voxel
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(2.0, 0.5, 0.6), perPixel * 0.5);  // fine fMRI: scale
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(8.0, 0.2, 0.6), 5.0);             // coarse SPECT: 5 mm
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(4.0, 2.0, 0.6), perPixel * 2.0);  // whole body
  // Through the plan: a 200 mm box (framing radius 100 sqrt 3) at 512 px, zoom 1.
  Volume ct({200, 200, 200}, 1, ScalarType::Int16, glm::dmat4(1.0));
  Volume pet({50, 50, 50}, 1, ScalarType::Float32,
             makeWorldFromIndex({}, {4, 4, 4}, glm::dmat3(1.0)));
  PlannedView v = planViews(studyWith({{"glyphs", nlohmann::json::object()}})).at(0);
  applyGlyphScale(v, ct, pet);
  const double mmPerPixel = 2.0 * render::framingSphere(ct).radius / 512.0;
  const double spacing = defaultGlyphSpacingMm(4.0, mmPerPixel, 0.6);
  EXPECT_DOUBLE_EQ(v.settings.glyphDiameterMm, 0.85 * spacing);
  EXPECT_NEAR(describeView(v.settings, "a", "").glyphSpacingMm.value_or(0), spacing, 1e-9);
  // A given spacing stays.
  PlannedView given = planViews(studyWith({{"glyphs", {{"spacing_mm", 7}}}})).at(0);
  applyGlyphScale(given, ct, pet);
  EXPECT_DOUBLE_EQ(given.settings.glyphDiameterMm, 0.85 * 7);
}

// Issue 15 item 4: labels chosen by number or by their AAL name (the label table beside the
// atlas, aal.nii.txt); "none" drops one; a name the table lacks, or a name without a table,
// is bad input naming the study.
TEST(GlyphLabels, ChosenByNumberOrAtlasName) {
  config::StudyConfig study = studyWith(
      {{"mode", "isosurface"},
       {"glyphs", {{"labels", {{"Hippocampus_L", "bumps"}, {"38", "dimples"}, {"7", "none"}}}}}});
  study.functional->path = test::sampleData("mricron/aal.nii.gz");
  study.functionalKind = config::FunctionalKind::Labels;
  const auto labels = planViews(study).at(0).settings.glyphLabels;
  ASSERT_EQ(labels.size(), 2u);
  // nlohmann::json keeps object keys sorted: "38" before "Hippocampus_L".
  EXPECT_EQ(labels[0], (render::LabelGlyph{38, true, "Hippocampus_R"}));
  EXPECT_EQ(labels[1], (render::LabelGlyph{37, false, "Hippocampus_L"}));
  const auto legend = glyphLegend(planViews(study).at(0), "", {0, 116});
  ASSERT_EQ(legend.entries.size(), 2u);
  EXPECT_EQ(legend.entries[1].label, "37 Hippocampus_L");
  EXPECT_TRUE(legend.entries[0].dimple);

  // planViews' refusal of the study as it stands ("" and a failure when it plans the views).
  auto refusal = [&study](const char* accepted) {
    try {
      planViews(study);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << accepted;
    return std::string();
  };
  study.render.views[0].glyphLabels[1].label = "Hippocampus_X";
  const std::string unknown = refusal("an unknown label name was accepted");
  EXPECT_NE(unknown.find("no label named 'Hippocampus_X' in"), std::string::npos) << unknown;
  // A table that gives one name to two labels is read, but that name cannot choose one.
  const std::filesystem::path dir = test::scratchDir();
  std::ofstream(dir / "twins.nii.txt") << "1 Twin\n2 Other\n3 Twin\n";
  std::filesystem::copy_file(test::sampleData("mricron/aal.nii.gz"), dir / "twins.nii.gz",
                             std::filesystem::copy_options::overwrite_existing);
  study.functional->path = dir / "twins.nii.gz";
  study.render.views[0].glyphLabels = {{"2", config::LabelGlyphKind::Bumps}};
  EXPECT_EQ(planViews(study).at(0).settings.glyphLabels.at(0).name, "Other");
  study.render.views[0].glyphLabels = {{"Twin", config::LabelGlyphKind::Bumps}};
  const std::string twin = refusal("a name given to two labels chose one");
  EXPECT_NE(twin.find("'Twin' names labels 1 and 3"), std::string::npos) << twin;
  study.functional->path = "/nonexistent/labels.nii.gz";
  EXPECT_THROW(planViews(study), InputError);
  study.functionalKind = config::FunctionalKind::Pet;
  EXPECT_THROW(planViews(study), InputError);
}

// The legend says what the bump sizes mean: none at or below the window, then the minimum
// size just above its low end up to full size at its high end (dimples below the middle for
// "both").
TEST(GlyphLegend, SizesFollowTheAttributeWindow) {
  PlannedView v =
      planViews(studyWith({{"glyphs", nlohmann::json::object()}, {"functional_window", {2.5, 8}}}))
          .at(0);
  const render::GlyphLegend legend = glyphLegend(v, "SUVbw", {0, 20});
  EXPECT_EQ(legend.title, "glyphs: SUVbw");
  ASSERT_EQ(legend.entries.size(), 4u);
  EXPECT_EQ(legend.entries[0].size, 0.0);
  EXPECT_EQ(legend.entries[1].label, "> 2.5");
  EXPECT_NEAR(legend.entries[1].size, 0.6, 1e-3);
  EXPECT_EQ(legend.entries[2].label, "5.25");
  EXPECT_DOUBLE_EQ(legend.entries[2].size, 0.8);
  EXPECT_DOUBLE_EQ(legend.entries[3].size, 1.0);
  v.settings.glyphConvexity = GlyphConvexity::Both;
  const render::GlyphLegend both = glyphLegend(v, "SUVbw", {0, 20});
  ASSERT_EQ(both.entries.size(), 5u);
  EXPECT_TRUE(both.entries[1].dimple);
  EXPECT_FALSE(both.entries[4].dimple);
  v.settings.glyphs = false;
  EXPECT_TRUE(glyphLegend(v, "SUVbw", {0, 20}).entries.empty());
}

TEST(AttributeDefaults, AViewsOwnWindowOrClassesWin) {
  const nlohmann::json glyphs = nlohmann::json::object();
  PlannedView own =
      planViews(studyWith({{"glyphs", glyphs}, {"functional_window", {1.0, 3.0}}})).at(0);
  applyAttributeDefaults(own, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(own.settings.functionalLow, 1.0);
  PlannedView classes = planViews(studyWith({{"glyphs", glyphs}, {"functional_classes", 4}})).at(0);
  applyAttributeDefaults(classes, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(classes.settings.functionalHigh, 0.0);
  PlannedView none = planViews(studyWith({{"glyphs", glyphs}})).at(0);
  applyAttributeDefaults(none, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(none.settings.functionalLow, 2.5);
  EXPECT_EQ(none.settings.functionalHigh, 10.0);
  // A colour overlay keeps the full range as its colour scale.
  PlannedView mpr = planViews(studyWith({{"mode", "mpr"}})).at(0);
  applyAttributeDefaults(mpr, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(mpr.settings.functionalHigh, 0.0);
}

// A study's 4D functional volume (the nipy fMRI: 20 frames) becomes one 3D volume with a note:
// the mean by default, or the frame the config names; a frame it lacks is bad input.
TEST(StudyLoader, A4DFunctionalVolumeContributesTheMeanOrTheChosenFrame) {
  const auto path = test::sampleData("nipy/functional.nii.gz");
  const Volume all = io::readVolume(path);
  ASSERT_EQ(all.components(), 20);
  config::VolumeSource source{path, "", config::defaultFrame(config::FunctionalKind::Fmri)};
  const Volume mean = readSource(source);
  EXPECT_EQ(mean.components(), 1);
  EXPECT_EQ(mean.dimensions(), all.dimensions());
  EXPECT_EQ(mean.worldFromIndex(), all.worldFromIndex());
  double sum = 0.0;
  for (int f = 0; f < 20; ++f) sum += all.value(8, 10, 1, f);
  EXPECT_NEAR(mean.value(8, 10, 1), sum / 20, 1e-3);
  EXPECT_NE(mean.metadata().notes.back().find("mean over all frames"), std::string::npos);
  source.frame = FrameChoice{false, 7};
  const Volume f7 = readSource(source);
  EXPECT_EQ(f7.value(8, 10, 1), all.value(8, 10, 1, 7));
  EXPECT_EQ(f7.metadata().notes.back(), "4D volume of 20 frames: frame 7 is used");
  source.frame = FrameChoice{false, 20};
  try {
    readSource(source);
    FAIL() << "frame 20 of 20 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.problem().find("20 frames (0 .. 19)"), std::string::npos) << e.what();
  }
  // No frame given (the anatomy's default): frame 0, said in a note.
  source.frame.reset();
  EXPECT_EQ(readSource(source).metadata().notes.back(), "4D volume of 20 frames: frame 0 is used");
}

}  // namespace
}  // namespace mvw::study
