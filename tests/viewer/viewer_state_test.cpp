// The viewer's state without a window or GL: what input does to the panes, the camera maths,
// the MPR window and colour maps, the readout, and the saved state. Its parts have their own
// tests: viewer_measurements_test, viewer_orbit_test, viewer_registration_test and
// viewer_requests_test.
#include "mvw/viewer/ViewerState.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "ViewerTestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"
#include "mvw/viewer/OpenedStudy.h"
#include "mvw/viewer/ViewControls.h"
#include "mvw/viewer/ViewerScript.h"

namespace mvw::viewer {
namespace {

using render::RenderMode;

using ViewerStateTest = ViewerFixture;

TEST_F(ViewerStateTest, OpensOnTheModalityDefaults) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  EXPECT_EQ(state.presetName(), "ct-bone");
  EXPECT_EQ(state.view3d().mode, RenderMode::Composite);
  EXPECT_DOUBLE_EQ(state.view3d().iso, 300.0);
  EXPECT_DOUBLE_EQ(state.mprWindow().window, 400.0);
  EXPECT_DOUBLE_EQ(state.mprWindow().level, 40.0);
  EXPECT_EQ(state.crosshair(), state.scene().centre);
  EXPECT_EQ(state.maximised(), -1);

  Volume mr = makeVolume("MR", 0.0, 500.0);
  ViewerState mrState(study, mr, nullptr, sceneOf(mr));
  EXPECT_EQ(mrState.presetName(), "mr-default");
  EXPECT_DOUBLE_EQ(mrState.view3d().iso, 200.0);
  EXPECT_DOUBLE_EQ(mrState.mprWindow().window, 500.0);
  EXPECT_DOUBLE_EQ(mrState.mprWindow().level, 250.0);
}

TEST_F(ViewerStateTest, PanesRenderWhenSizedAndDirty) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  EXPECT_FALSE(state.needsRender(k3d));  // no size yet
  state.setPaneSize(k3d, {7, 100});
  EXPECT_FALSE(state.needsRender(k3d));  // too small to render
  renderAll(state);
  EXPECT_FALSE(state.anyDirty());
  state.setPaneSize(kAxial, {64, 48});  // unchanged
  EXPECT_FALSE(state.anyDirty());
  state.setPaneSize(kAxial, {65, 48});
  EXPECT_TRUE(state.needsRender(kAxial));
  EXPECT_FALSE(state.needsRender(k3d));
}

TEST_F(ViewerStateTest, DraggingRendersTheThreeDPaneCoarseThenRefines) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.drag(k3d, 0.1, 0.0, MouseButton::Left, false);
  const render::RenderSettings coarse = state.renderSettings(k3d, true);
  EXPECT_EQ(coarse.size, glm::ivec2(32, 24));
  EXPECT_DOUBLE_EQ(coarse.stepMm, 2.0);  // twice the smallest spacing
  state.rendered(k3d, {}, Image(32, 24), true);
  EXPECT_TRUE(state.needsRender(k3d));  // the full-resolution frame follows the drag
  EXPECT_EQ(state.renderSettings(k3d).size, glm::ivec2(64, 48));
}

TEST_F(ViewerStateTest, DragResolutionFollowsTheDragFramesTime) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.drag(k3d, 0.1, 0.0, MouseButton::Left, false);
  // Slow drag frames coarsen it one step a frame, up to a sixth of the pane a side.
  for (int divisor : {3, 4, 5, 6, 6}) {
    state.rendered(k3d, {}, Image(8, 8), true, 2.0 * ViewerState::kDragFrameBudgetMs);
    EXPECT_EQ(state.dragDivisor(), divisor);
    const render::RenderSettings s = state.renderSettings(k3d, true);
    EXPECT_EQ(s.size, glm::max(glm::ivec2(64, 48) / divisor, glm::ivec2(8)));
    EXPECT_DOUBLE_EQ(s.stepMm, divisor * 1.0);  // that many times the smallest spacing
  }
  // Frames within the budget keep it; fast ones refine it back to half size, no further.
  state.rendered(k3d, {}, Image(8, 8), true, 0.9 * ViewerState::kDragFrameBudgetMs);
  EXPECT_EQ(state.dragDivisor(), 6);
  for (int divisor : {5, 4, 3, 2, 2}) {
    state.rendered(k3d, {}, Image(8, 8), true, 0.2 * ViewerState::kDragFrameBudgetMs);
    EXPECT_EQ(state.dragDivisor(), divisor);
  }
  // Full-resolution frames and MPR panes do not count.
  state.rendered(k3d, {}, Image(64, 48), false, 1000.0);
  state.rendered(kAxial, {}, Image(64, 48), true, 1000.0);
  EXPECT_EQ(state.dragDivisor(), 2);
  EXPECT_EQ(state.renderSettings(k3d).size, glm::ivec2(64, 48));
}

TEST_F(ViewerStateTest, ThreeDDragsRotateZoomAndPan) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.drag(k3d, 0.25, 0.1, MouseButton::Left, false);
  EXPECT_DOUBLE_EQ(state.view3d().camera.azimuthDeg, 45.0);
  EXPECT_DOUBLE_EQ(state.view3d().camera.elevationDeg, 18.0);
  EXPECT_TRUE(state.needsRender(k3d));
  EXPECT_FALSE(state.needsRender(kAxial));
  state.drag(k3d, 0.0, 1.0, MouseButton::Left, false);
  EXPECT_DOUBLE_EQ(state.view3d().camera.elevationDeg, 89.0);  // never over the pole
  state.drag(k3d, 0.0, -0.5, MouseButton::Right, false);
  EXPECT_NEAR(state.view3d().camera.zoom, std::exp(1.0), 1e-12);
  const double zoom = state.view3d().camera.zoom;
  state.drag(k3d, 0.1, 0.2, MouseButton::Middle, false);
  const double mm = 2.0 * 10.0 / zoom;
  EXPECT_NEAR(state.view3d().camera.panMm.x, -0.1 * mm, 1e-12);
  EXPECT_NEAR(state.view3d().camera.panMm.y, 0.2 * mm, 1e-12);
  state.wheel(k3d, 1000.0);
  EXPECT_DOUBLE_EQ(state.view3d().camera.zoom, 20.0);
}

TEST_F(ViewerStateTest, MprRightOrCtrlDragSetsWindowAndLevel) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.drag(kAxial, 0.1, 0.0, MouseButton::Left, false);  // a plain left drag is the crosshair's
  EXPECT_FALSE(state.anyDirty());
  state.drag(kCoronal, 0.5, 0.1, MouseButton::Right, false);
  EXPECT_NEAR(state.mprWindow().window, 400.0 * std::exp(1.0), 1e-9);
  EXPECT_NEAR(state.mprWindow().level, 40.0 - 0.1 * 3000.0 * 0.5, 1e-9);
  EXPECT_FALSE(state.needsRender(k3d));
  EXPECT_TRUE(state.needsRender(kAxial) && state.needsRender(kCoronal) &&
              state.needsRender(kSagittal));
  state.drag(kSagittal, -100.0, 0.0, MouseButton::Left, true);
  EXPECT_DOUBLE_EQ(state.mprWindow().window, 1e-3);  // never zero or negative
  const render::RenderSettings s = state.renderSettings(kAxial);
  EXPECT_EQ(s.mode, RenderMode::Mpr);
  EXPECT_EQ(s.window, state.mprWindow());
}

TEST_F(ViewerStateTest, WheelScrollsSlicesAndClicksMoveTheCrosshairInPlane) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  const glm::dvec3 centre = state.scene().centre;
  const render::Camera axial = state.paneCamera(kAxial);
  state.wheel(kAxial, 3);  // three slices of the finest spacing (1 mm)
  EXPECT_NEAR(glm::length(state.crosshair() - (centre + 3.0 * axial.forward)), 0.0, 1e-12);
  EXPECT_NEAR(state.renderSettings(kAxial).planeOffsetMm, 3.0, 1e-12);
  EXPECT_FALSE(state.needsRender(k3d));
  // A click right of the axial pane's centre: along the pane's right, still on its plane.
  state.click(kAxial, 0.75, 0.5);
  const glm::dvec3 moved = state.crosshair() - centre;
  EXPECT_NEAR(glm::dot(moved, axial.forward), 3.0, 1e-9);
  EXPECT_NEAR(glm::dot(moved, axial.up), 0.0, 1e-9);
  EXPECT_NEAR(glm::dot(moved, axial.right), 0.5 * axial.halfHeightMm * axial.aspect, 1e-9);
  EXPECT_EQ(state.onPlane(kAxial, 0.75, 0.5), state.crosshair());
  const glm::dvec3 before = state.crosshair();
  state.click(k3d, 0.1, 0.1);  // the 3D pane has no plane
  EXPECT_EQ(state.crosshair(), before);
  state.key('R', false);
  EXPECT_EQ(state.crosshair(), centre);
}

TEST_F(ViewerStateTest, KeysSwitchModesAndToggles) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  renderAll(state);
  state.key('3', false);
  EXPECT_EQ(state.view3d().mode, RenderMode::Mip);
  EXPECT_TRUE(state.needsRender(k3d) && state.needsRender(kSagittal));
  state.key('5', false);
  EXPECT_EQ(state.view3d().mode, RenderMode::Average);
  state.key('D', false);
  EXPECT_TRUE(state.view3d().depthCue.on);
  EXPECT_DOUBLE_EQ(state.view3d().depthCue.amount, 0.66);
  EXPECT_DOUBLE_EQ(state.view3d().depthCue.contrast, 0.33);
  state.key('D', false);
  EXPECT_FALSE(state.view3d().depthCue.on);
  EXPECT_DOUBLE_EQ(state.view3d().depthCue.amount, 0.0);
  EXPECT_DOUBLE_EQ(state.view3d().depthCue.contrast, 1.0);
  state.key('G', false);
  state.key('F', false);
  EXPECT_TRUE(state.view3d().glyphs.on);
  EXPECT_TRUE(state.view3d().overlay.fusion);
  const std::string preset = state.presetName();
  state.key('P', false);
  EXPECT_NE(state.presetName(), preset);
  state.key('S', false);
  EXPECT_EQ(state.requests().takeScreenshotRequest(), std::filesystem::path("mvw-screenshot.png"));
  EXPECT_EQ(state.requests().takeScreenshotRequest(), std::nullopt);
  renderAll(state);
  state.key('Q', false);  // unbound: nothing to redraw
  EXPECT_FALSE(state.anyDirty());
  state.drag(k3d, 0.5, 0.0, MouseButton::Left, false);
  state.key('R', false);
  EXPECT_DOUBLE_EQ(state.view3d().camera.azimuthDeg, 0.0);
}

// Issue 41: the fusion key works in every projection of the 3D pane, and the caption says so
// only while it is on; the spin keeps it.
TEST_F(ViewerStateTest, FusionKeyFusesTheProjections) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  for (char mode : {'3', '4', '5'}) {
    renderAll(state);
    state.key(mode, false);
    state.key('F', false);
    EXPECT_TRUE(state.view3d().overlay.fusion) << mode;
    EXPECT_TRUE(state.needsRender(k3d));
    const std::string caption = state.caption(k3d, state.renderSettings(k3d));
    EXPECT_NE(caption.find("+ colour fusion (functional max)"), std::string::npos) << caption;
    state.key('O', false);  // spin: the fused settings turn
    EXPECT_TRUE(state.renderSettings(k3d).overlay.fusion);
    state.key('O', false);
    state.key('F', false);
    EXPECT_FALSE(state.view3d().overlay.fusion) << mode;
    EXPECT_EQ(state.caption(k3d, state.renderSettings(k3d)).find("fusion"), std::string::npos);
  }
}

TEST_F(ViewerStateTest, GlyphAndFusionKeysNeedAFunctionalVolume) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.key('G', false);
  state.key('F', false);
  EXPECT_FALSE(state.view3d().glyphs.on);
  EXPECT_FALSE(state.view3d().overlay.fusion);
  EXPECT_FALSE(state.anyDirty());
  EXPECT_EQ(state.requests().status(), "colour fusion needs a functional volume");
  state.registration().start();  // nothing to register
  EXPECT_FALSE(state.registration().running());
}

TEST_F(ViewerStateTest, MprPanesShareTheFunctionalWindowOfTheThreeDPane) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  state.view3d().functionalWindow = {2.0, 7.0};
  state.view3d().functionalClasses = 5;
  state.view3d().overlay.opacity = 0.75f;
  const render::RenderSettings s = state.renderSettings(kCoronal);
  EXPECT_DOUBLE_EQ(s.functionalWindow.low, 2.0);
  EXPECT_DOUBLE_EQ(s.functionalWindow.high, 7.0);
  EXPECT_EQ(s.functionalClasses, 5);
  EXPECT_FLOAT_EQ(s.overlay.opacity, 0.75f);
  EXPECT_EQ(s.camera.view, render::StandardView::Anterior);
  EXPECT_EQ(state.renderSettings(kAxial).camera.view, render::StandardView::Inferior);
  EXPECT_EQ(state.renderSettings(kSagittal).camera.view, render::StandardView::Left);
}

// The PET/CT reading layout (issue 36 item 2): the MPR slots show one plane, the anatomical one
// without the overlay, the functional one alone (full opacity over a black anatomy), the fused
// one as the standard MPR; the 3D slot is the functional volume's MIP; key L cycles the layouts.
TEST_F(ViewerStateTest, PetCtLayoutShowsOnePlaneInStepAndTheFunctionalMip) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  renderAll(state);
  EXPECT_FALSE(state.paneShowsFunctional(k3d));
  state.setLayout(config::ViewerLayout::PetCtCoronal);
  EXPECT_TRUE(state.orbit().mode() == Orbit::Spin);  // the rotating MIP
  for (int p = kAxial; p <= kSagittal; ++p)
    EXPECT_EQ(state.renderSettings(p).camera.view, render::StandardView::Anterior) << p;
  const render::RenderSettings anatomy = state.renderSettings(kAxial);
  const render::RenderSettings functional = state.renderSettings(kCoronal);
  const render::RenderSettings fused = state.renderSettings(kSagittal);
  EXPECT_FALSE(anatomy.overlay.mpr);
  EXPECT_TRUE(fused.overlay.mpr);
  EXPECT_FLOAT_EQ(fused.overlay.opacity, 0.5f);
  EXPECT_FLOAT_EQ(functional.overlay.opacity, 1.0f);
  EXPECT_LT(functional.overlay.threshold, 0.0f);
  ASSERT_TRUE(functional.imageColors);
  for (const auto& rgb : functional.imageColors->rgb) EXPECT_EQ(rgb[0] + rgb[1] + rgb[2], 0);
  ASSERT_TRUE(functional.overlayColors);
  EXPECT_EQ(functional.overlayColors->map, ColorMap::GreyInverted);
  // One crosshair: the three slots cut the plane through it.
  EXPECT_DOUBLE_EQ(anatomy.planeOffsetMm, fused.planeOffsetMm);
  renderAll(state);  // the panes' cameras, which the wheel moves along
  state.wheel(kSagittal, 3.0);
  EXPECT_DOUBLE_EQ(state.renderSettings(kAxial).planeOffsetMm,
                   state.renderSettings(kSagittal).planeOffsetMm);
  EXPECT_NE(state.renderSettings(kAxial).planeOffsetMm, anatomy.planeOffsetMm);
  EXPECT_TRUE(state.paneShowsFunctional(k3d));
  const render::RenderSettings mip = state.renderSettings(k3d);
  EXPECT_EQ(mip.mode, RenderMode::Mip);
  // The functional volume alone, MIP and pane, in its own window from the data (the 99.5th
  // percentile of the voxels above the background: here its one hot voxel, 10), not the
  // overlay's or the glyphs' (the scene's range here, 0 .. 1).
  const auto [dlo, dhi] = state.functionalDisplayWindow();
  EXPECT_DOUBLE_EQ(dlo, 0.0);
  EXPECT_DOUBLE_EQ(dhi, 10.0);
  EXPECT_DOUBLE_EQ(mip.window.level - 0.5 * mip.window.window, dlo);
  EXPECT_DOUBLE_EQ(mip.window.level + 0.5 * mip.window.window, dhi);
  EXPECT_DOUBLE_EQ(functional.functionalWindow.low, dlo);
  EXPECT_DOUBLE_EQ(functional.functionalWindow.high, dhi);
  EXPECT_NE(fused.functionalWindow.high, dhi);  // the fused pane keeps the overlay's window
  EXPECT_EQ(state.paneCell(kAxial), 0);
  EXPECT_EQ(state.paneCell(kCoronal), 1);
  EXPECT_EQ(state.paneCell(kSagittal), 2);
  EXPECT_EQ(state.paneCell(k3d), 3);
  EXPECT_EQ(ViewerState::paneNamed("fused"), kSagittal);
  EXPECT_EQ(ViewerState::paneNamed("mip"), k3d);
  state.key('L', false);
  EXPECT_EQ(state.layout(), config::ViewerLayout::PetCtSagittal);
  state.key('L', false);
  EXPECT_EQ(state.layout(), config::ViewerLayout::Standard);
  EXPECT_TRUE(state.orbit().mode() == Orbit::Off);
  EXPECT_FALSE(state.paneShowsFunctional(k3d));
  EXPECT_EQ(state.renderSettings(kCoronal).overlay.opacity, 0.5f);
  EXPECT_EQ(state.paneCell(k3d), 0);
}

// A config's zoom keeps its field in a pane of another shape (issue 36 item 4): a 3D view zoomed
// 2 for a 256 x 512 portrait shows the same height in a landscape pane, not half of it.
TEST_F(ViewerStateTest, AStudysZoomKeepsItsFieldInAPaneOfAnotherShape) {
  config::ViewConfig portrait;
  portrait.name = "portrait";
  portrait.mode = RenderMode::Mip;
  portrait.zoom = 2.0;
  portrait.width = 256;
  portrait.height = 512;
  study.render.views = {portrait};
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  state.setPaneSize(k3d, {518, 440});
  const render::RenderSettings s = state.renderSettings(k3d);
  const double r = state.scene().radius;
  const render::Camera pane = render::makeCamera(s.camera, state.scene().centre, r, s.size);
  const render::Camera own =
      render::makeCamera(s.camera, state.scene().centre, r, {portrait.width, portrait.height});
  EXPECT_NEAR(pane.halfHeightMm, own.halfHeightMm, 1e-9);  // the portrait's whole height
  EXPECT_NEAR(own.halfHeightMm, 2.0 * r / 2.0, 1e-9);
}

// Issue 52 item 4: the 3D pane's glyphs take the spacing `mvw render` derives for the study's
// view at the pane's size (study::applyGlyphScale), so a maximised pane reads as a render at
// its size does; a spacing set on the panel stays.
TEST_F(ViewerStateTest, GlyphSpacingFollowsThePaneSizeAsARenderAtThatSize) {
  config::ViewConfig glyphs;
  glyphs.name = "glyphs";
  glyphs.mode = RenderMode::Composite;
  glyphs.glyphs.on = true;
  study.render.views = {glyphs};
  study.functional.emplace();
  study.functional->path = "pet.nii.gz";
  ViewerScene scene = sceneOf(ct);
  scene.functionalRange = {0.0, 10.0};
  // `mvw render`'s spacing for the view at a size.
  auto renderedAt = [&](glm::ivec2 size) {
    config::StudyConfig at = study;
    at.render.views[0].width = size.x, at.render.views[0].height = size.y;
    std::vector<study::PlannedView> planned = study::planViews(at);
    study::prepareViews(planned, at, ct, &pet, scene.functionalRange);
    return glyphSpacingMm(planned.at(0).settings);
  };
  const glm::ivec2 window{24, 16}, maximised{400, 300};  // the pixel floor decides the first
  ASSERT_GT(renderedAt(window), 1.5 * renderedAt(maximised));
  ViewerState state(study, ct, &pet, scene);
  state.setPaneSize(k3d, window);
  EXPECT_DOUBLE_EQ(glyphSpacingMm(state.renderSettings(k3d)), renderedAt(window));
  state.setPaneSize(k3d, maximised);
  EXPECT_DOUBLE_EQ(glyphSpacingMm(state.renderSettings(k3d)), renderedAt(maximised));
  EXPECT_DOUBLE_EQ(glyphSpacingMm(state.renderSettings(k3d, true)), renderedAt(maximised));
  setGlyphSpacingMm(state.view3d(), 7.0);  // the panel's slider
  state.setPaneSize(k3d, window);
  EXPECT_NEAR(glyphSpacingMm(state.renderSettings(k3d)), 7.0, 1e-9);
}

TEST_F(ViewerStateTest, CaptionsNameTheModeAndWindow) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  EXPECT_EQ(state.caption(k3d, state.renderSettings(k3d)), "composite  ct-bone");
  // The same captions as `mvw render` burns in (study::viewCaption).
  EXPECT_EQ(state.caption(kAxial, state.renderSettings(kAxial)), "mpr axial  W 400 L 40");
  state.key('3', false);
  EXPECT_EQ(state.caption(k3d, state.renderSettings(k3d)), "mip  W 3000 L 500");  // full range
  state.key('2', false);
  EXPECT_EQ(state.caption(k3d, state.renderSettings(k3d)), "isosurface  iso 300");
}

// A PET opened alone, from a folder or the PACS (issue 51 item 3): not washed out by its
// hottest voxels. 315 voxels at SUV 1.5, one at 0 and one at 19.5: the panes at 0-5 SUV, the
// 3D pane its grey-inverted MIP, and every pane's colour bar (the grey MPR panes' too) says so.
TEST_F(ViewerStateTest, APetAloneOpensAtItsSuvWindowWithAColourBarOnEveryPane) {
  Volume suv = makeVolume("PT", 0.0, 19.5);
  suv.metadata().unit = "SUVbw";
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i)
        if ((i + j + k) % 16 != 0) suv.setValue(i, j, k, 0, 1.5);
  ViewerState state(study, suv, nullptr, sceneOf(suv));
  EXPECT_EQ(state.view3d().mode, RenderMode::Mip);
  ASSERT_TRUE(state.view3d().imageColors.has_value());
  EXPECT_EQ(state.view3d().imageColors->map, ColorMap::GreyInverted);
  EXPECT_DOUBLE_EQ(state.view3d().window.window, 5.0);
  EXPECT_DOUBLE_EQ(state.mprWindow().window, 5.0);
  EXPECT_DOUBLE_EQ(state.mprWindow().level, 2.5);
  renderAll(state);
  const std::filesystem::path file = test::scratchDir() / "panes.json";
  writePaneReport(state, file);
  const nlohmann::json panes = nlohmann::json::parse(std::ifstream(file))["panes"];
  ASSERT_EQ(panes.size(), 4u);
  for (const nlohmann::json& p : panes) {
    SCOPED_TRACE(p.dump());
    EXPECT_EQ(p["window"], nlohmann::json({0.0, 5.0}));
    ASSERT_TRUE(p["colour_bar"].is_object());
    EXPECT_EQ(p["colour_bar"]["low"], 0.0);
    EXPECT_EQ(p["colour_bar"]["high"], 5.0);
    EXPECT_EQ(p["colour_bar"]["unit"], "SUVbw");
  }
  EXPECT_EQ(panes[0]["mode"], "mip");
  EXPECT_EQ(panes[0]["colour_bar"]["colormap"], "grey-inverted");
  EXPECT_EQ(panes[1]["colour_bar"]["colormap"], "grey");
  // The PET/CT layout: the functional pane (the PET itself) in grey-inverted at 0-5 SUV too.
  state.setLayout(config::ViewerLayout::PetCtAxial);
  writePaneReport(state, file);
  const nlohmann::json petCt = nlohmann::json::parse(std::ifstream(file))["panes"];
  EXPECT_EQ(petCt[kCoronal]["colour_bar"]["colormap"], "grey-inverted");
  EXPECT_EQ(petCt[kCoronal]["colour_bar"]["high"], 5.0);
  EXPECT_EQ(petCt[k3d]["colour_bar"]["high"], 5.0);
}

// Without SUV (no weight or dose: Bq/ml) every pane's caption and colour bar and the readout
// say "no SUV", the caption and readout why.
TEST_F(ViewerStateTest, APetWithoutSuvSaysSoOnEveryPaneAndInTheReadout) {
  Volume bq = makeVolume("PT", 0.0, 9000.0);
  bq.metadata().unit = "Bq/ml";
  bq.metadata().notes = {
      "values in Bq/ml: SUVbw not computed (PatientWeight missing or not positive)"};
  bq.setValue(5, 3, 2, 0, 4200.0);
  ViewerState state(study, bq, nullptr, sceneOf(bq));
  EXPECT_EQ(state.view3d().mode, RenderMode::Mip);
  renderAll(state);
  const std::filesystem::path file = test::scratchDir() / "panes.json";
  writePaneReport(state, file);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(file));
  for (const nlohmann::json& p : report["panes"]) {
    SCOPED_TRACE(p.dump());
    EXPECT_NE(p["caption"].get<std::string>().find("no SUV: PatientWeight missing or not positive"),
              std::string::npos);
    EXPECT_EQ(p["colour_bar"]["unit"], "Bq/ml, no SUV");
  }
  EXPECT_EQ(state.readout({1.0, 0.0, 3.0}),
            "PET 4200 Bq/ml (no SUV: PatientWeight missing or not positive)");
  EXPECT_NE(report["readout"].get<std::string>().find("(no SUV: PatientWeight"), std::string::npos);
}

TEST_F(ViewerStateTest, MaximiseTogglesOnePane) {
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  state.toggleMaximised(kCoronal);
  EXPECT_EQ(state.maximised(), kCoronal);
  state.toggleMaximised(kCoronal);
  EXPECT_EQ(state.maximised(), -1);
}

TEST_F(ViewerStateTest, SavedStateReopensAsTheSameViews) {
  const auto dir = test::scratchDir();
  ct.metadata().sourcePath = (dir / "ct.nii.gz").string();
  std::ofstream(ct.metadata().sourcePath) << "";  // the loader checks the path exists
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.key('3', false);
  state.key('D', false);
  state.drag(k3d, 0.1, 0.05, MouseButton::Left, false);
  state.drag(kAxial, 0.2, 0.1, MouseButton::Right, false);
  state.saveConfig(dir / "saved.json");

  const config::StudyConfig saved = config::loadStudyConfig(dir / "saved.json");
  EXPECT_EQ(saved.name, "saved from mvw view");
  EXPECT_EQ(saved.anatomical.path, ct.metadata().sourcePath);
  ASSERT_EQ(saved.render.views.size(), 4u);
  EXPECT_EQ(saved.render.views[0].name, "view-3d");
  EXPECT_EQ(saved.render.views[1].name, "view-axial");
  ViewerState reopened(saved, ct, nullptr, sceneOf(ct));
  EXPECT_EQ(reopened.view3d().mode, RenderMode::Mip);
  EXPECT_TRUE(reopened.view3d().depthCue.on);
  EXPECT_NEAR(reopened.view3d().camera.azimuthDeg, 18.0, 1e-9);
  EXPECT_NEAR(reopened.view3d().camera.elevationDeg, 9.0, 1e-9);
  EXPECT_NEAR(reopened.mprWindow().window, state.mprWindow().window, 1e-6);
  EXPECT_NEAR(reopened.mprWindow().level, state.mprWindow().level, 1e-6);
}

// Zoom and pan on the MPR panes (issue 36 item 1): linked, a point panned into view on one
// pane is panned on the panes that share its axis, the keys fit and 1:1, and the state saves
// and restores them.
TEST_F(ViewerStateTest, MprPanesZoomAndPanTogether) {
  const auto dir = test::scratchDir();
  ct.metadata().sourcePath = (dir / "ct.nii.gz").string();
  std::ofstream(ct.metadata().sourcePath) << "";
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  const glm::dvec3 crosshair = state.crosshair();
  state.wheel(kAxial, 2.0, true);  // Ctrl+wheel: zoom, not a slice
  EXPECT_EQ(state.crosshair(), crosshair);
  for (int p = kAxial; p < kPaneCount; ++p)
    EXPECT_NEAR(state.renderSettings(p).camera.zoom, std::exp(0.2), 1e-12) << p;
  EXPECT_DOUBLE_EQ(state.renderSettings(k3d).camera.zoom, 1.0);
  state.zoomPane(kCoronal, 2.0);
  EXPECT_NEAR(state.mprZoom(), 2.0 * std::exp(0.2), 1e-12);

  // The axial pane's picture 10 mm right, 4 mm up: the world moves by that much in its plane;
  // the coronal pane shares its left-right axis, the sagittal its anterior-posterior one.
  state.panPane(kAxial, 10.0, 4.0);
  const auto panOf = [&](int p) { return state.renderSettings(p).camera.panMm; };
  EXPECT_NEAR(panOf(kAxial).x, 10.0, 1e-9);
  EXPECT_NEAR(panOf(kAxial).y, 4.0, 1e-9);
  EXPECT_NEAR(std::abs(panOf(kCoronal).x), 10.0, 1e-9);
  EXPECT_NEAR(panOf(kCoronal).y, 0.0, 1e-9);
  EXPECT_NEAR(std::abs(panOf(kSagittal).x), 4.0, 1e-9);
  EXPECT_NEAR(panOf(kSagittal).y, 0.0, 1e-9);
  // A middle drag over half the pane's width moves the picture by half its width in mm.
  renderAll(state);
  const render::Camera& axial = state.paneCamera(kAxial);
  const glm::dvec2 before = panOf(kAxial);
  state.drag(kAxial, 0.5, 0.0, MouseButton::Middle, false);
  EXPECT_NEAR(panOf(kAxial).x - before.x, axial.halfHeightMm * axial.aspect, 1e-9);

  state.saveConfig(dir / "saved.json");
  ViewerState reopened(config::loadStudyConfig(dir / "saved.json"), ct, nullptr, sceneOf(ct));
  EXPECT_NEAR(reopened.mprZoom(), state.mprZoom(), 1e-9);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(reopened.mprPan()[a], state.mprPan()[a], 1e-9) << a;

  // C: the crosshair in the middle of every MPR pane.
  state.click(kAxial, 0.8, 0.3);
  state.click(kCoronal, 0.8, 0.7);
  state.key('C', false);
  renderAll(state);
  for (int p = kAxial; p < kPaneCount; ++p) {
    const glm::dvec4 clip = state.paneCamera(p).clipFromWorld * glm::dvec4(state.crosshair(), 1.0);
    EXPECT_NEAR(clip.x / clip.w, 0.0, 1e-9) << p;
    EXPECT_NEAR(clip.y / clip.w, 0.0, 1e-9) << p;
  }
  state.key('Z', false);  // fit
  EXPECT_DOUBLE_EQ(state.mprZoom(), 1.0);
  EXPECT_EQ(state.mprPan(), glm::dvec3(0.0));
  state.key('X', false);  // one screen pixel per voxel of the finest spacing (1 mm here)
  renderAll(state);
  const render::Camera& one = state.paneCamera(kAxial);
  EXPECT_NEAR(2.0 * one.halfHeightMm / 48.0, ct.smallestSpacing(), 1e-9);
}

// No silent black panes (issue 36 item 5): a PET in SUV opens with its own isovalue (SUV 2.5,
// not the config's 300 HU), P offers no CT preset, and a pane whose frame is one colour says why.
TEST_F(ViewerStateTest, NoSilentEmptyPanes) {
  Volume suv = makeVolume("PT", 0.0, 19.0);  // int16 voxels
  suv.metadata().unit = "SUVbw";
  ViewerState state(study, suv, nullptr, sceneOf(suv));
  EXPECT_DOUBLE_EQ(state.view3d().iso, 2.5);
  EXPECT_EQ(state.presetName(), "pet-hot-metal");
  for (int i = 0; i < 6; ++i) {
    state.key('P', false);
    EXPECT_EQ(state.presetName().rfind("ct-", 0), std::string::npos) << state.presetName();
  }
  state.key('2', false);
  state.view3d().iso = 300.0;
  for (int p = 0; p < kPaneCount; ++p) state.setPaneSize(p, {64, 48});
  const render::RenderSettings s = state.renderSettings(k3d);
  const render::Camera cam =
      render::makeCamera(s.camera, state.scene().centre, state.scene().radius, s.size);
  state.rendered(k3d, cam, Image(64, 48), false);  // one colour: nothing shows
  EXPECT_EQ(state.emptyPaneMessage(k3d),
            "Nothing to show: the isovalue 300 lies outside the volume's values (0 .. 19 "
            "SUVbw); set the iso value in the panel");
  Image some(64, 48);
  some.rgba[4 * 100] = 200;
  state.rendered(k3d, cam, some, false);
  EXPECT_EQ(state.emptyPaneMessage(k3d), "");
  EXPECT_EQ(state.emptyPaneMessage(kAxial), "");  // not rendered yet
}

// Jumping through the places a PET reader looks at (issue 36 item 4): the hottest voxel, each
// segment, each ROI, round again; the MPR panes centre on each.
TEST_F(ViewerStateTest, JumpGoesToTheHottestVoxelSegmentsAndRois) {
  ct.setValue(7, 2, 3, 0, 3000.0);  // the hottest voxel: (3, -1, 5.5) mm
  ViewerScene scene = sceneOf(ct);
  scene.segmentCentres = {{"Neoplasm, Primary", {1.0, 2.0, 3.0}}};
  ViewerState state(study, ct, nullptr, scene);
  state.measurements().addSphere({{{-2.0, 1.0, 0.5}}, 2.0});
  EXPECT_EQ(state.jumpNext(), "the hottest voxel");
  EXPECT_EQ(state.crosshair(), glm::dvec3(3.0, -1.0, 5.5));
  EXPECT_EQ(state.mprPan(), state.scene().centre - state.crosshair());
  EXPECT_EQ(state.requests().status(),
            "jump 1/3: the hottest voxel at 3.0, -1.0, 5.5 mm LPS (J: next)");
  EXPECT_EQ(state.jumpNext(), "segment \"Neoplasm, Primary\"");
  EXPECT_EQ(state.crosshair(), glm::dvec3(1.0, 2.0, 3.0));
  state.key('J', false);
  EXPECT_EQ(state.crosshair(), glm::dvec3(-2.0, 1.0, 0.5));
  EXPECT_EQ(state.jumpNext(), "the hottest voxel");  // round again
}

TEST_F(ViewerStateTest, DumpWritesThePaneAsRendered) {
  const auto dir = test::scratchDir();
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  renderAll(state);
  state.dump(kSagittal, dir / "sagittal.png");
  EXPECT_TRUE(std::filesystem::exists(dir / "sagittal.png"));
}

TEST_F(ViewerStateTest, ProbeReadsTheNearestVoxel) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  const ViewerProbe corner = state.probe({-4.2, -3.0, -2.0});
  EXPECT_TRUE(corner.anatomicalInside);
  EXPECT_DOUBLE_EQ(corner.anatomical, -1000.0);
  EXPECT_TRUE(corner.functionalInside);
  EXPECT_DOUBLE_EQ(corner.functional, 0.0);
  EXPECT_FALSE(state.probe({100.0, 0.0, 0.0}).anatomicalInside);
}

// The readout names both volumes with their units at the anatomical voxel under the cursor;
// the functional value is the renderer's: through the placement, trilinear between centres.
TEST_F(ViewerStateTest, ReadoutShowsBothValuesWhereTheRendererSamplesThem) {
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i) pet.setValue(i, j, k, 0, i);  // a ramp along L
  pet.metadata().unit = "SUVbw";
  ct.setValue(5, 3, 2, 0, 45.0);
  ViewerScene scene = sceneOf(ct);
  scene.anatomicalFromFunctional = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.0, 0.0));
  ViewerState state(study, ct, &pet, scene);
  // Voxel (5, 3, 2) is at (1, 0, 3) mm; 0.3 mm off it still reads that voxel.
  const ViewerProbe p = state.probe({1.3, 0.2, 3.4});
  EXPECT_EQ(p.at, glm::dvec3(1.0, 0.0, 3.0));
  EXPECT_DOUBLE_EQ(p.anatomical, 45.0);
  ASSERT_TRUE(p.functionalInside);
  EXPECT_NEAR(p.functional, 4.5, 1e-12);  // half way between functional voxels 4 and 5
  EXPECT_EQ(state.readout({1.3, 0.2, 3.4}), "CT 45 HU | PET 4.5 SUVbw");
  EXPECT_EQ(state.readout({50.0, 0.0, 0.0}), "CT outside | PET outside");
  // Placed 2 mm posterior, the functional box ends before the anatomy's first row (y = -3
  // mm): past half a voxel beyond the last centre is outside.
  scene.anatomicalFromFunctional = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 2.0, 0.0));
  ViewerState moved(study, ct, &pet, scene);
  EXPECT_EQ(moved.readout({1.0, -3.0, 3.0}), "CT 0 HU | PET outside");
  EXPECT_EQ(moved.readout({1.0, -1.0, 3.0}), "CT 0 HU | PET 5 SUVbw");
}

// Two volumes of one modality read apart (issue 36 item 3): each by its series description or
// file name, and a value without a unit says so.
TEST_F(ViewerStateTest, ReadoutNamesVolumesByDescriptionOrFileAndSaysNoUnit) {
  Volume t1 = makeVolume("MR", 0.0, 500.0);
  t1.metadata().seriesDescription = "mocoMEMPRAGE_220FOV RMS";
  t1.metadata().unit = "";
  Volume cbf = makeVolume("MR", 0.0, 900.0);
  cbf.metadata().sourcePath = "/data/study/relCBF.nii.gz";
  cbf.metadata().unit = "ml/100g/min";
  t1.setValue(5, 3, 2, 0, 346.0);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i) cbf.setValue(i, j, k, 0, 314.0);
  ViewerState state(study, t1, &cbf, sceneOf(t1));
  EXPECT_EQ(state.readout({1.0, 0.0, 3.0}),
            "MR mocoMEMPRAGE_220FOV RMS 346 (no unit) | MR relCBF 314 ml/100g/min");
  EXPECT_EQ(ViewerState::volumeName(t1, "anatomical"), "MR mocoMEMPRAGE_220FOV RMS");
  Volume wholeBody = makeVolume("PT", 0.0, 1.0);
  wholeBody.metadata().seriesDescription = "PET WB_0";  // not "PET PET WB_0"
  EXPECT_EQ(ViewerState::volumeName(wholeBody, "anatomical"), "PET WB_0");
  wholeBody.metadata().seriesDescription = "Petrous bone";
  EXPECT_EQ(ViewerState::volumeName(wholeBody, "anatomical"), "PET Petrous bone");
  Volume bare = makeVolume("", 0.0, 1.0);
  EXPECT_EQ(ViewerState::volumeName(bare, "functional"), "functional");
  bare.metadata().seriesDescription = "a very long series description indeed";
  EXPECT_EQ(ViewerState::volumeName(bare, "functional"), "a very long series des..");
}

TEST(ViewerStateText, PaneNames) {
  for (int p = 0; p < kPaneCount; ++p)
    EXPECT_EQ(ViewerState::paneNamed(ViewerState::paneName(p)), p);
  EXPECT_EQ(ViewerState::paneNamed("oblique"), std::nullopt);
}

TEST_F(ViewerStateTest, ColourMapChoosersReachThePanes) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  EXPECT_EQ(state.colormap(ColorTarget::View3d), ColorMap::Grey);
  EXPECT_EQ(state.colormap(ColorTarget::Mpr), ColorMap::Grey);
  EXPECT_EQ(state.colormap(ColorTarget::Overlay), ColorMap::HotMetal);
  EXPECT_FALSE(state.renderSettings(kAxial).imageColors);
  EXPECT_FALSE(state.renderSettings(kAxial).overlayColors);
  renderAll(state);
  state.setColormap(ColorTarget::View3d, ColorMap::GreyInverted);
  EXPECT_TRUE(state.needsRender(k3d));
  state.setColormap(ColorTarget::Mpr, ColorMap::HotIron);
  state.setColormap(ColorTarget::Overlay, ColorMap::Pet);
  ASSERT_TRUE(state.renderSettings(k3d).imageColors);
  EXPECT_EQ(state.renderSettings(k3d).imageColors->map, ColorMap::GreyInverted);
  EXPECT_EQ(state.renderSettings(k3d).imageColors->rgb[0],
            (std::array<std::uint8_t, 3>{255, 255, 255}));
  for (int p = kAxial; p < kPaneCount; ++p) {
    ASSERT_TRUE(state.renderSettings(p).imageColors);
    EXPECT_EQ(state.renderSettings(p).imageColors->map, ColorMap::HotIron);
    ASSERT_TRUE(state.renderSettings(p).overlayColors);
    EXPECT_EQ(state.renderSettings(p).overlayColors->map, ColorMap::Pet);
  }
  state.key('3', false);
  EXPECT_EQ(state.caption(k3d, state.renderSettings(k3d)), "mip  W 3000 L 500  grey-inverted");
  // Back to the defaults: no tables at all, so the renderer draws what it always drew.
  state.setColormap(ColorTarget::View3d, ColorMap::Grey);
  state.setColormap(ColorTarget::Overlay, ColorMap::HotMetal);
  EXPECT_FALSE(state.renderSettings(k3d).imageColors);
  EXPECT_FALSE(state.renderSettings(kAxial).overlayColors);
}

TEST_F(ViewerStateTest, TheStudysColourMapsOpenTheViewerAndAreSaved) {
  const auto dir = test::scratchDir();
  ct.metadata().sourcePath = (dir / "ct.nii.gz").string();
  std::ofstream(ct.metadata().sourcePath) << "";
  config::ViewConfig mip;
  mip.name = "mip";
  mip.mode = RenderMode::Mip;
  mip.colormap = ColorMap::GreyInverted;
  config::ViewConfig mpr;
  mpr.name = "mpr";
  mpr.mode = RenderMode::Mpr;
  mpr.colormap = ColorMap::HotIron;
  study.render.views = {mip, mpr};
  ViewerState state(study, ct, nullptr, sceneOf(ct));
  EXPECT_EQ(state.colormap(ColorTarget::View3d), ColorMap::GreyInverted);
  EXPECT_EQ(state.colormap(ColorTarget::Mpr), ColorMap::HotIron);
  renderAll(state);
  state.saveConfig(dir / "saved.json");
  const config::StudyConfig saved = config::loadStudyConfig(dir / "saved.json");
  ASSERT_EQ(saved.render.views.size(), 4u);
  EXPECT_EQ(saved.render.views[0].colormap, ColorMap::GreyInverted);
  EXPECT_EQ(saved.render.views[1].colormap, ColorMap::HotIron);
}

// The panel's label picker and the script's glyph-label (issue 15 items 4 and 8): chosen
// labels carry the atlas's names, reach the 3D pane's settings, and are saved and reopened.
TEST_F(ViewerStateTest, ChosenGlyphLabelsReachTheRendererAndAreSaved) {
  const auto dir = test::scratchDir();
  ct.metadata().sourcePath = (dir / "ct.nii.gz").string();
  std::ofstream(ct.metadata().sourcePath) << "";
  Volume atlas = makeVolume("", 0.0, 3.0);
  atlas.metadata().sourcePath = (dir / "atlas.nii.gz").string();
  std::ofstream(atlas.metadata().sourcePath) << "";
  std::ofstream(dir / "atlas.nii.txt") << "1 Precentral_L\n2 Precentral_R\n3 Frontal_Sup_L\n";
  study.functional.emplace();
  study.functional->path = atlas.metadata().sourcePath;
  study.functionalKind = config::FunctionalKind::Labels;
  ViewerScene scene = sceneOf(ct);
  scene.functionalRange = {0.0, 3.0};
  ViewerState state(study, ct, &atlas, scene);
  ASSERT_EQ(state.labelNames().size(), 3u);
  renderAll(state);
  state.key('G', false);  // glyphs on: the config writes the glyphs object only then
  ViewerScript script = ViewerScript::parse(
      "glyph-label 3 rings\nglyph-label 2 dimples\nglyph-label 1 bumps\nglyph-label 1 none\n",
      dir / "labels.txt");
  while (script.step(state)) {
  }
  EXPECT_TRUE(state.needsRender(k3d) || !state.paneRendered(k3d));
  const std::vector<render::LabelGlyph> expected = {{2, GlyphKind::Dimples, "Precentral_R"},
                                                    {3, GlyphKind::Rings, "Frontal_Sup_L"}};
  EXPECT_EQ(state.view3d().glyphLabels, expected);
  ASSERT_TRUE(state.view3d().glyphs.on);
  EXPECT_EQ(state.glyphLegend(k3d, state.renderSettings(k3d)).entries.size(), 2u);
  state.saveConfig(dir / "saved.json");
  const config::StudyConfig saved = config::loadStudyConfig(dir / "saved.json");
  ASSERT_EQ(saved.render.views.size(), 4u);
  const std::vector<config::LabelChoice> written = {{"2", config::LabelGlyphKind::Dimples},
                                                    {"3", config::LabelGlyphKind::Rings}};
  EXPECT_EQ(saved.render.views[0].glyphLabels, written);
  EXPECT_TRUE(saved.render.views[1].glyphLabels.empty());  // an MPR pane draws no glyphs
  ViewerState reopened(saved, ct, &atlas, scene);
  EXPECT_EQ(reopened.view3d().glyphLabels, expected);
}

}  // namespace
}  // namespace mvw::viewer
