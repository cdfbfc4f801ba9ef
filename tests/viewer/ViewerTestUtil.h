#pragma once
// Shared by the viewer's unit tests (one file per class of modules/viewer): small volumes whose
// anisotropic grid shows a wrong axis or spacing, the scene the renderer would report for them,
// and every pane rendered once, so clicks and the wheel have cameras to move along.
#include <string>

#include <gtest/gtest.h>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {

// Intentional odd, anisotropic grid: a wrong axis or spacing shows in the wheel and click maths.
inline Volume makeVolume(const std::string& modality, double lo, double hi) {
  Volume v({9, 7, 5}, 1, ScalarType::Int16,
           makeWorldFromIndex({-4.0, -3.0, -2.0}, {1.0, 1.0, 2.5}, glm::dmat3(1.0)));
  v.setValue(0, 0, 0, 0, lo);
  v.setValue(8, 6, 4, 0, hi);
  v.metadata().modality = modality;
  v.metadata().unit = modality == "CT" ? "HU" : "";
  return v;
}

inline ViewerScene sceneOf(const Volume& v) {
  ViewerScene s;
  s.centre = v.worldFromIndexPoint(glm::dvec3(v.dimensions() - 1) * 0.5);
  s.radius = 10.0;
  s.valueRange = v.valueRange();
  return s;
}

// Every pane sized and rendered once, with the cameras the renderer would report.
inline void renderAll(ViewerState& state) {
  for (int p = 0; p < kPaneCount; ++p) {
    state.setPaneSize(p, {64, 48});
    const render::RenderSettings s = state.renderSettings(p);
    state.rendered(p,
                   render::makeCamera(s.camera, state.scene().centre, state.scene().radius, s.size),
                   Image(s.size.x, s.size.y), false);
  }
}

// A CT and a PET volume on the same grid, and an empty study; each test file names it after
// the class it tests (using ViewerMeasurementsTest = ViewerFixture).
class ViewerFixture : public ::testing::Test {
 protected:
  config::StudyConfig study;
  Volume ct = makeVolume("CT", -1000.0, 2000.0);
  Volume pet = makeVolume("PT", 0.0, 10.0);
};

}  // namespace mvw::viewer
