// Sphere ROIs and rulers on the MPR panes: drawn by a gesture, their statistics those of
// `mvw stats`, where they show on each pane, and saved and restored with the state.
#include "mvw/viewer/ViewerMeasurements.h"

#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "TestUtil.h"
#include "ViewerTestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {
namespace {

using ViewerMeasurementsTest = ViewerFixture;

// A sphere drawn on an MPR pane: centre where the drag starts (on the pane's plane), radius
// the drag's length in mm; its statistics are roiStatistics over sphereVoxels in each volume
// (the functional one at the centre moved by the placement), and a click draws nothing.
TEST_F(ViewerMeasurementsTest, SphereRoiDrawnByADragHasTheStatsOfMvwStats) {
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i) {
        ct.setValue(i, j, k, 0, i * 10 + j + k * 100);
        pet.setValue(i, j, k, 0, 0.1 * (i + j + k));
      }
  pet.metadata().unit = "SUVbw";
  ViewerScene scene = sceneOf(ct);
  scene.anatomicalFromFunctional = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 0.0, 0.0));
  ViewerState state(study, ct, &pet, scene);
  renderAll(state);
  state.measurements().beginGesture(kAxial, MprTool::Sphere, 0.5, 0.5);
  EXPECT_TRUE(state.measurements().measuring());
  state.measurements().moveGesture(0.5, 0.5);
  state.measurements().endGesture();  // a click
  EXPECT_TRUE(state.measurements().all().spheres.empty());
  state.measurements().beginGesture(kAxial, MprTool::Sphere, 0.5, 0.5);
  state.measurements().moveGesture(0.6, 0.5);
  ASSERT_TRUE(state.measurements().pendingSphere().has_value());
  state.measurements().endGesture();
  ASSERT_EQ(state.measurements().all().spheres.size(), 1u);
  const config::SphereMeasurement& sphere = state.measurements().all().spheres[0];
  const glm::dvec3 centre = state.onPlane(kAxial, 0.5, 0.5);
  EXPECT_EQ(glm::dvec3(sphere.centre[0], sphere.centre[1], sphere.centre[2]), centre);
  EXPECT_NEAR(sphere.radiusMm, glm::distance(centre, state.onPlane(kAxial, 0.6, 0.5)), 1e-12);
  EXPECT_GT(sphere.radiusMm, 1.0);

  const SphereStatistics& st = state.measurements().sphereStatistics().at(0);
  study::StatsOptions hu;
  const study::RoiStats a =
      study::roiStatistics(ct, study::sphereVoxels(ct, {centre, sphere.radiusMm}), hu);
  ASSERT_TRUE(st.anatomical.has_value());
  EXPECT_EQ(st.anatomical->voxels, a.voxels);
  EXPECT_EQ(st.anatomical->mean, a.mean);
  EXPECT_EQ(st.anatomical->sd, a.sd);
  EXPECT_EQ(st.anatomical->max, a.max);
  EXPECT_FALSE(st.anatomical->peak.has_value());  // HU: no SUVpeak
  study::StatsOptions suv;
  suv.peak = true;
  const glm::dvec3 fc = centre - glm::dvec3(1.0, 0.0, 0.0);
  const study::RoiStats f =
      study::roiStatistics(pet, study::sphereVoxels(pet, {fc, sphere.radiusMm}), suv);
  ASSERT_TRUE(st.functional.has_value());
  EXPECT_EQ(st.functionalCentre, fc);
  EXPECT_EQ(st.functional->voxels, f.voxels);
  EXPECT_EQ(st.functional->mean, f.mean);
  ASSERT_TRUE(st.functional->peak.has_value());
  EXPECT_EQ(*st.functional->peak, *f.peak);
  EXPECT_EQ(st.functional->unit, "SUVbw");

  // A sphere outside the volumes says so instead of statistics.
  state.measurements().addSphere({{500.0, 0.0, 0.0}, 2.0});
  EXPECT_FALSE(state.measurements().sphereStatistics().at(1).anatomical.has_value());
  EXPECT_FALSE(state.measurements().sphereStatistics().at(1).anatomicalProblem.empty());
}

// The circle a sphere cuts from each MPR pane's plane (through the crosshair); a ruler's ends
// on its pane, shown only on the plane it lies in.
// Where the panel draws the cursor readout and the crosshair: onPlane's inverse.
TEST_F(ViewerMeasurementsTest, WorldPointsOnThePanes) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  for (int pane : {kAxial, kCoronal, kSagittal}) {
    const glm::dvec2 middle = state.measurements().toPane(pane, state.crosshair());
    EXPECT_NEAR(middle.x, 0.5, 1e-9);
    EXPECT_NEAR(middle.y, 0.5, 1e-9);
    const glm::dvec2 f = state.measurements().toPane(pane, state.onPlane(pane, 0.25, 0.8));
    EXPECT_NEAR(f.x, 0.25, 1e-9);
    EXPECT_NEAR(f.y, 0.8, 1e-9);
  }
}

TEST_F(ViewerMeasurementsTest, SpheresAndRulersOnThePanes) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  const glm::dvec3 c = state.crosshair();
  const glm::dvec3 forward = state.paneCamera(kAxial).forward;
  const config::SphereMeasurement sphere{
      {c.x + 3 * forward.x, c.y + 3 * forward.y, c.z + 3 * forward.z}, 5.0};
  const auto axial = state.measurements().paneCircle(kAxial, sphere);
  ASSERT_TRUE(axial.has_value());
  EXPECT_NEAR(axial->radiusMm, 4.0, 1e-9);  // sqrt(5^2 - 3^2)
  EXPECT_NEAR(axial->centre.x, 0.5, 1e-9);
  EXPECT_NEAR(axial->centre.y, 0.5, 1e-9);
  // 4 mm over the pane's width in mm (the camera's extent along `right`).
  const double widthMm =
      glm::distance(state.onPlane(kAxial, 0.0, 0.5), state.onPlane(kAxial, 1.0, 0.5));
  EXPECT_NEAR(axial->radius.x, 4.0 / widthMm, 1e-9);
  EXPECT_FALSE(state.measurements()
                   .paneCircle(kAxial, {sphere.centre, 2.9})
                   .has_value());  // misses the plane
  EXPECT_FALSE(state.measurements().paneCircle(k3d, sphere).has_value());

  state.measurements().beginGesture(kCoronal, MprTool::Ruler, 0.25, 0.5);
  state.measurements().moveGesture(0.75, 0.5);
  state.measurements().endGesture();
  ASSERT_EQ(state.measurements().all().rulers.size(), 1u);
  const config::RulerMeasurement& r = state.measurements().all().rulers[0];
  EXPECT_NEAR(ViewerMeasurements::rulerLengthMm(r),
              glm::distance(state.onPlane(kCoronal, 0.25, 0.5), state.onPlane(kCoronal, 0.75, 0.5)),
              1e-12);
  const PaneSegment seg = state.measurements().paneSegment(kCoronal, r);
  EXPECT_TRUE(seg.inPlane);
  EXPECT_NEAR(seg.from.x, 0.25, 1e-9);
  EXPECT_NEAR(seg.to.x, 0.75, 1e-9);
  state.wheel(kCoronal, 2);  // two slices on: the ruler stays, on its own slice
  EXPECT_FALSE(state.measurements().paneSegment(kCoronal, r).inPlane);
  EXPECT_EQ(state.measurements().all().rulers.size(), 1u);
}

// The spheres and rulers are saved with the state (the study's "measurements") and a state
// opened from the saved file has them, with the same statistics; so has segmentation_outlines.
TEST_F(ViewerMeasurementsTest, MeasurementsAndOutlinesAreSavedAndRestored) {
  const auto dir = test::scratchDir();
  ct.metadata().sourcePath = (dir / "ct.nii.gz").string();
  std::ofstream(ct.metadata().sourcePath) << "";
  for (int i = 0; i < 9; ++i) ct.setValue(i, 3, 2, 0, 7.0 * i);
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.measurements().addSphere({{0.5, 0.0, 0.0}, 2.5});
  state.measurements().addRuler({{-3.0, -2.0, 0.0}, {3.0, 2.0, 0.0}});
  state.setSegmentOutlines(false);
  EXPECT_FALSE(state.renderSettings(kAxial).segmentationOutlines);
  state.saveConfig(dir / "saved.json");

  const config::StudyConfig saved = config::loadStudyConfig(dir / "saved.json");
  EXPECT_EQ(saved.measurements, state.measurements().all());
  EXPECT_FALSE(saved.render.views[1].segmentationOutlines);
  ViewerState reopened(saved, ct, nullptr, sceneOf(ct));
  EXPECT_EQ(reopened.measurements().all(), state.measurements().all());
  EXPECT_FALSE(reopened.renderSettings(kAxial).segmentationOutlines);
  ASSERT_EQ(reopened.measurements().sphereStatistics().size(), 1u);
  ASSERT_TRUE(reopened.measurements().sphereStatistics()[0].anatomical.has_value());
  EXPECT_EQ(reopened.measurements().sphereStatistics()[0].anatomical->voxels,
            state.measurements().sphereStatistics()[0].anatomical->voxels);
  EXPECT_EQ(reopened.measurements().sphereStatistics()[0].anatomical->mean,
            state.measurements().sphereStatistics()[0].anatomical->mean);
  EXPECT_GT(reopened.measurements().sphereStatistics()[0].anatomical->voxels, 0u);
  reopened.measurements().clear();
  EXPECT_TRUE(reopened.measurements().all().spheres.empty());
  EXPECT_TRUE(reopened.measurements().sphereStatistics().empty());
  ViewerState defaults(study, ct, nullptr, sceneOf(ct));
  EXPECT_TRUE(defaults.renderSettings(kAxial).segmentationOutlines);
}

}  // namespace
}  // namespace mvw::viewer
