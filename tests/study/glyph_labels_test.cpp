// Glyphs on a label volume (study ViewPlan): labels chosen by number or by their atlas name,
// on the fetched AAL atlas, and the names that cannot choose one refused.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "StudyTestUtil.h"
#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/study/Caption.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

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
  EXPECT_EQ(labels[0], (render::LabelGlyph{38, GlyphKind::Dimples, "Hippocampus_R"}));
  EXPECT_EQ(labels[1], (render::LabelGlyph{37, GlyphKind::Bumps, "Hippocampus_L"}));
  const auto legend = glyphLegend(planViews(study).at(0), "", {0, 116});
  ASSERT_EQ(legend.entries.size(), 2u);
  EXPECT_EQ(legend.entries[1].label, "37 Hippocampus_L");
  EXPECT_EQ(legend.entries[0].kind, GlyphKind::Dimples);

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

// Issue 40: chosen labels and classes take glyph kinds; the legend names each kind (and, for
// classes of the attribute window, the value range); an unknown kind is bad input naming the
// key; bumps and dimples alone keep the old shading (no kinds variant).
TEST(GlyphLabels, KindsForLabelsAndClasses) {
  config::StudyConfig study = studyWith(
      {{"mode", "isosurface"},
       {"glyphs", {{"labels", {{"Hippocampus_L", "rings"}, {"38", "crosses"}, {"7", "none"}}}}}});
  study.functional->path = test::sampleData("mricron/aal.nii.gz");
  study.functionalKind = config::FunctionalKind::Labels;
  const PlannedView view = planViews(study).at(0);
  ASSERT_EQ(view.settings.glyphLabels.size(), 2u);
  EXPECT_EQ(view.settings.glyphLabels[0],
            (render::LabelGlyph{38, GlyphKind::Crosses, "Hippocampus_R"}));
  EXPECT_EQ(view.settings.glyphLabels[1],
            (render::LabelGlyph{37, GlyphKind::Rings, "Hippocampus_L"}));
  EXPECT_TRUE(render::usesGlyphKinds(view.settings));
  const render::GlyphLegend legend = glyphLegend(view, "", {0, 116});
  ASSERT_EQ(legend.entries.size(), 2u);
  EXPECT_EQ(legend.entries[1].label, "37 Hippocampus_L  rings");
  EXPECT_EQ(legend.entries[1].kind, GlyphKind::Rings);
  EXPECT_EQ(legend.entries[1].value, 37.0);  // the icon is rendered at this label
  // Saved and read again: the same kinds.
  const nlohmann::json saved = config::viewConfigJson(study.render.views[0]);
  EXPECT_EQ(saved["glyphs"]["labels"]["Hippocampus_L"], "rings");
  // Bumps and dimples only: the "both" shading as before.
  study.render.views[0].glyphLabels = {{"37", config::LabelGlyphKind::Dimples}};
  EXPECT_FALSE(render::usesGlyphKinds(planViews(study).at(0).settings));
  // An unknown kind, and class kinds that are not a list of kinds.
  auto bad = [](const nlohmann::json& glyphs) {
    try {
      studyWith({{"mode", "isosurface"}, {"glyphs", glyphs}});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(bad({{"labels", {{"3", "stars"}}}}).find("glyphs.labels.3"), std::string::npos);
  EXPECT_NE(bad({{"class_kinds", {"rings", "stars"}}}).find("class_kinds[1]"), std::string::npos);
  EXPECT_NE(bad({{"class_kinds", nlohmann::json::array()}}).find("class_kinds"), std::string::npos);

  // Classes of the attribute window: five equal ranges, each its kind and value range.
  config::StudyConfig pet =
      studyWith({{"mode", "isosurface"},
                 {"functional_window", {1.0, 6.0}},
                 {"glyphs", {{"class_kinds", {"bumps", "rings", "ridges", "cones", "crosses"}}}}});
  PlannedView ordinal;
  ordinal.config = pet.render.views[0];
  ordinal.settings.glyphs.on = true;
  ordinal.settings.functionalWindow = {1.0, 6.0};
  ordinal.settings.glyphs.classKinds = pet.render.views[0].glyphs.classKinds;
  const render::GlyphLegend ranges = glyphLegend(ordinal, "SUVbw", {0, 10});
  ASSERT_EQ(ranges.entries.size(), 6u);
  EXPECT_EQ(ranges.entries[0].label, "<= 1  none");
  EXPECT_EQ(ranges.entries[2].label, "2 - 3  rings");
  EXPECT_EQ(ranges.entries[5].label, "5 - 6+  crosses");
  EXPECT_EQ(ranges.entries[4].kind, GlyphKind::Cones);
  EXPECT_DOUBLE_EQ(*ranges.entries[2].value, 2.5);
  // With kinds the default spacing keeps a glyph kGlyphKindRadiusPixels in radius.
  EXPECT_NEAR(defaultGlyphSpacingMm(2.0, 0.5, 0.6, true),
              kGlyphKindRadiusPixels * 0.5 / (0.5 * kBlueNoiseDiameterFraction), 1e-9);
  EXPECT_LT(defaultGlyphSpacingMm(2.0, 0.5, 0.6, false),
            defaultGlyphSpacingMm(2.0, 0.5, 0.6, true));
}

}  // namespace
}  // namespace mvw::study
