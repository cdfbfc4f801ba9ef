// Defaults by modality (study ModalityDefaults), so a study needs no settings to look right:
// the anatomy's preset and window, and the functional attribute window by kind and unit.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "StudyTestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/study/ModalityDefaults.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

Volume volumeOf(const std::string& modality, const std::string& unit) {
  Volume v({2, 2, 2}, 1, ScalarType::Int16, glm::dmat4(1.0));
  v.metadata().modality = modality;
  v.metadata().unit = unit;
  return v;
}

TEST(ModalityDefaults, CtGetsBoneAndTheSoftTissueWindowMrTheRange) {
  const ModalityDefaults ct = modalityDefaults(volumeOf("CT", "HU"), {-1024, 3071});
  EXPECT_EQ(ct.preset, "ct-bone");
  EXPECT_EQ(ct.iso, 300.0);
  EXPECT_EQ(ct.mpr.window, 400.0);
  EXPECT_EQ(ct.mpr.level, 40.0);
  const ModalityDefaults mr = modalityDefaults(volumeOf("MR", ""), {0, 1000});
  EXPECT_EQ(mr.preset, "mr-default");
  EXPECT_EQ(mr.iso, 400.0);
  EXPECT_EQ(mr.mpr.window, 1000.0);
  EXPECT_EQ(mr.mpr.level, 500.0);
  EXPECT_EQ(defaultPreset(volumeOf("PT", "SUVbw")), "pet-hot-metal");
  EXPECT_EQ(defaultPreset(volumeOf("", "HU")), "ct-bone");  // HU without a modality: a CT
}
TEST(AttributeDefaults, PetInSuvFromTheLesionThresholdOtherUnitsFrom41Percent) {
  const Volume suv = volumeOf("PT", "SUVbw");
  const auto a = defaultAttributeWindow(config::FunctionalKind::Pet, suv, {0.0, 19.5});
  ASSERT_TRUE(a.set());
  EXPECT_EQ(a.low, 2.5);
  EXPECT_EQ(a.high, 19.5);
  // No uptake above 2.5: a valid window that shows none.
  const auto none = defaultAttributeWindow(config::FunctionalKind::Pet, suv, {0.0, 1.8});
  ASSERT_TRUE(none.set());
  EXPECT_EQ(none.low, 2.5);
  EXPECT_GT(none.high, 2.5);
  // Bq/ml, or a NIfTI PET without a unit: relative to the maximum.
  const auto bq = defaultAttributeWindow(config::FunctionalKind::Pet, volumeOf("", ""), {0, 4.0});
  ASSERT_TRUE(bq.set());
  EXPECT_DOUBLE_EQ(bq.low, 0.41 * 4.0);
  EXPECT_EQ(bq.high, 4.0);
  // The modality alone says PET too; fMRI, labels and the rest keep the full range.
  EXPECT_TRUE(
      defaultAttributeWindow(config::FunctionalKind::Other, volumeOf("NM", ""), {0, 9}).set());
  EXPECT_FALSE(
      defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("MR", ""), {0, 9}).set());
  // An fMRI statistic map (z or t from the NIfTI intent code): from z = 2.3.
  const auto z = defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("", "z"), {-4, 9});
  ASSERT_TRUE(z.set());
  EXPECT_EQ(z.low, 2.3);
  EXPECT_EQ(z.high, 9.0);
  EXPECT_FALSE(
      defaultAttributeWindow(config::FunctionalKind::Fmri, volumeOf("", "t"), {-4, 2}).set());
  EXPECT_FALSE(
      defaultAttributeWindow(config::FunctionalKind::Labels, volumeOf("", ""), {0, 9}).set());
}
// The PET/CT layout's functional pane (issue 36): a CBF-like volume of 1000 voxels, background
// 0, tissue 300 .. 796 evenly and two hot voxels (a vessel) at 5000: 0 to the 99.5th
// percentile of the voxels above the background, not to the vessel; SUV at 0-5 or 0-10.
TEST(FunctionalDisplayWindow, ARobustRangeFromTheDataOrSuvFiveOrTen) {
  Volume cbf({10, 10, 10}, 1, ScalarType::Float32, glm::dmat4(1.0));
  for (int n = 0; n < 1000; ++n) {
    const int i = n % 10, j = n / 10 % 10, k = n / 100;
    cbf.setValue(i, j, k, 0, n < 500 ? 0.0 : n < 998 ? 300.0 + (n - 500) : 5000.0);
  }
  const auto w = defaultFunctionalDisplayWindow(cbf, cbf.valueRange());
  EXPECT_EQ(w.low, 0.0);
  // 500 voxels above 0: the sorted 300 .. 797 and 5000, 5000; the 99.5th percentile is
  // element floor(0.995 * 499) = 496, the value 796.
  EXPECT_EQ(w.high, 796.0);
  // Values below 0 in a z map: from the 1st percentile of the voxels above the minimum;
  // elsewhere (an ASL CBF's negative noise) from 0.
  Volume z({10, 10, 10}, 1, ScalarType::Float32, glm::dmat4(1.0));
  z.metadata().unit = "z";
  for (int n = 0; n < 1000; ++n) z.setValue(n % 10, n / 10 % 10, n / 100, 0, n / 100.0 - 5.0);
  const auto zw = defaultFunctionalDisplayWindow(z, z.valueRange());
  EXPECT_NEAR(zw.low, -4.9, 1e-5);   // element floor(0.01 * 998) = 9 of -4.99 .. 4.99
  EXPECT_NEAR(zw.high, 4.94, 1e-5);  // element floor(0.995 * 998) = 993
  z.metadata().unit = "ml/100g/min";
  EXPECT_EQ(defaultFunctionalDisplayWindow(z, z.valueRange()).low, 0.0);
  // SUV: 0-5 (here three hot voxels above it), or 0-10 where more than 0.5 % of the voxels
  // above the background lie above SUV 5.
  Volume suv({10, 10, 10}, 1, ScalarType::Float32, glm::dmat4(1.0));
  suv.metadata().unit = "SUVbw";
  for (int n = 0; n < 1000; ++n)
    suv.setValue(n % 10, n / 10 % 10, n / 100, 0, n < 500 ? 0.0 : n < 997 ? 1.5 : 19.5);
  EXPECT_EQ(defaultFunctionalDisplayWindow(suv, suv.valueRange()).high, 5.0);
  for (int n = 900; n < 1000; ++n) suv.setValue(n % 10, n / 10 % 10, n / 100, 0, 7.0);
  EXPECT_EQ(defaultFunctionalDisplayWindow(suv, suv.valueRange()).high, 10.0);
}

// A PET read alone (issue 51 item 3), from a folder or the PACS with no view or window of its
// own: 1000 voxels, half background, 1.5 SUV, three hot voxels at 19.5. Not the full range
// (W 19.5) that washes it out: 0-5 SUV, its MIP grey-inverted; without SUV 0 to the 99.5th
// percentile, and why not SUV.
Volume wholeBody(const std::string& unit) {
  Volume v({10, 10, 10}, 1, ScalarType::Float32, glm::dmat4(1.0));
  v.metadata().modality = "PT";
  v.metadata().unit = unit;
  for (int n = 0; n < 1000; ++n)
    v.setValue(n % 10, n / 10 % 10, n / 100, 0, n < 500 ? 0.0 : n < 997 ? 1.5 : 19.5);
  return v;
}

TEST(ModalityDefaults, APetAloneOpensAsAMipAtZeroToFiveSuv) {
  const Volume suv = wholeBody("SUVbw");
  const ModalityDefaults d = modalityDefaults(suv, suv.valueRange());
  EXPECT_EQ(d.preset, "pet-hot-metal");
  EXPECT_EQ(d.iso, 2.5);
  EXPECT_EQ(d.mpr.window, 5.0);
  EXPECT_EQ(d.mpr.level, 2.5);
  EXPECT_EQ(d.mode3d, RenderMode::Mip);
  EXPECT_EQ(d.mipColors, ColorMap::GreyInverted);
  EXPECT_TRUE(isEmission(suv));
  EXPECT_EQ(noSuvNote(suv), "");
  // CT and MR keep their composite.
  EXPECT_EQ(modalityDefaults(volumeOf("CT", "HU"), {-1024, 3071}).mode3d, RenderMode::Composite);
  EXPECT_EQ(modalityDefaults(volumeOf("MR", ""), {0, 900}).mode3d, RenderMode::Composite);
  EXPECT_FALSE(isEmission(volumeOf("MR", "")));
  EXPECT_TRUE(isEmission(volumeOf("NM", "")));
}

TEST(ModalityDefaults, APetWithoutSuvGetsItsOwnRangeAndSaysWhy) {
  Volume bq = wholeBody("Bq/ml");
  for (int n = 500; n < 997; ++n) bq.setValue(n % 10, n / 10 % 10, n / 100, 0, n * 10.0);
  const ModalityDefaults d = modalityDefaults(bq, bq.valueRange());
  // 500 voxels above 0: 5000 .. 9960 and three at 19.5 (below them); sorted, element
  // floor(0.995 * 499) = 496 is 9930.
  EXPECT_DOUBLE_EQ(d.mpr.level - 0.5 * d.mpr.window, 0.0);
  EXPECT_DOUBLE_EQ(d.mpr.level + 0.5 * d.mpr.window, 9930.0);
  EXPECT_EQ(d.mode3d, RenderMode::Mip);
  bq.metadata().notes = {"a note on something else",
                         "values in Bq/ml: SUVbw not computed (PatientWeight missing or not "
                         "positive)"};
  EXPECT_EQ(noSuvNote(bq), "no SUV: PatientWeight missing or not positive");
  bq.metadata().notes = {"SUV conversion turned off: values in Bq/ml"};
  EXPECT_EQ(noSuvNote(bq), "no SUV: SUV conversion turned off: values in Bq/ml");
  bq.metadata().notes.clear();
  EXPECT_EQ(noSuvNote(bq), "no SUV: values in Bq/ml");
  EXPECT_EQ(noSuvNote(volumeOf("PT", "")), "no SUV: values in no unit");
  EXPECT_EQ(noSuvNote(volumeOf("CT", "HU")), "");  // only emission images have an SUV to miss
}

// The rule reaches `mvw render` and the viewer through the planned views: the view a config
// without views gets (implied) is the PET's MIP, and MIP and MPR views without a window get
// the PET's; a view's own window, a composite and a CT stay as they are.
TEST(ModalityDefaults, ViewsWithoutAWindowOfAPetAloneGetThePets) {
  const Volume suv = wholeBody("SUVbw");
  const ModalityDefaults d = modalityDefaults(suv, suv.valueRange());
  config::StudyConfig study = studyWith(nlohmann::json::object());
  study.render.views[0].implied = true;
  PlannedView implied = planViews(study).at(0);
  applyModalityView(implied, suv, d);
  EXPECT_EQ(implied.settings.mode, RenderMode::Mip);
  EXPECT_EQ(implied.config.mode, RenderMode::Mip);
  ASSERT_TRUE(implied.settings.imageColors.has_value());
  EXPECT_EQ(implied.settings.imageColors->map, ColorMap::GreyInverted);
  EXPECT_EQ(implied.settings.window, (WindowLevel{5.0, 2.5}));
  PlannedView mpr = planViews(studyWith({{"mode", "mpr"}})).at(0);
  applyModalityView(mpr, suv, d);
  EXPECT_EQ(mpr.settings.window.window, 5.0);
  EXPECT_FALSE(mpr.settings.imageColors.has_value());  // a view's own colour map (grey) stays
  PlannedView own = planViews(studyWith({{"mode", "mip"}, {"window", 8}, {"level", 4}})).at(0);
  applyModalityView(own, suv, d);
  EXPECT_EQ(own.settings.window.window, 8.0);
  PlannedView composite = planViews(studyWith(nlohmann::json::object())).at(0);
  applyModalityView(composite, suv, d);
  EXPECT_EQ(composite.settings.mode, RenderMode::Composite);
  EXPECT_FALSE(composite.settings.window.set());
  PlannedView ct = planViews(study).at(0);
  applyModalityView(ct, volumeOf("CT", "HU"), d);
  EXPECT_EQ(ct.settings.mode, RenderMode::Composite);
}

TEST(AttributeDefaults, AViewsOwnWindowOrClassesWin) {
  const nlohmann::json glyphs = nlohmann::json::object();
  PlannedView own =
      planViews(studyWith({{"glyphs", glyphs}, {"functional_window", {1.0, 3.0}}})).at(0);
  applyAttributeDefaults(own, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(own.settings.functionalWindow.low, 1.0);
  PlannedView classes = planViews(studyWith({{"glyphs", glyphs}, {"functional_classes", 4}})).at(0);
  applyAttributeDefaults(classes, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(classes.settings.functionalWindow.high, 0.0);
  PlannedView none = planViews(studyWith({{"glyphs", glyphs}})).at(0);
  applyAttributeDefaults(none, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(none.settings.functionalWindow.low, 2.5);
  EXPECT_EQ(none.settings.functionalWindow.high, 10.0);
  // A colour overlay keeps the full range as its colour scale.
  PlannedView mpr = planViews(studyWith({{"mode", "mpr"}})).at(0);
  applyAttributeDefaults(mpr, config::FunctionalKind::Pet, volumeOf("PT", "SUVbw"), {0, 10});
  EXPECT_EQ(mpr.settings.functionalWindow.high, 0.0);
}

}  // namespace
}  // namespace mvw::study
