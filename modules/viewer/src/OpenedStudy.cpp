#include "mvw/viewer/OpenedStudy.h"

#include "mvw/core/WindowLevel.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/viewer/ViewerRegistration.h"

namespace mvw::viewer {

ViewerScene studyScene(const study::Session& session, const render::VolumeRenderer& renderer) {
  const Volume* functional = session.functional();
  ViewerScene scene;
  if (functional) {
    scene.registration = ViewerRegistration::describePlacement(
        config::toString(session.config().registration.method), session.placement()->report);
    scene.functionalRange = renderer.functionalRange();
    scene.anatomicalFromFunctional = session.anatomicalFromFunctional();
  }
  if (const study::SegmentOverlay* segments = session.segments())
    scene.segmentCentres = segmentCentres(
        *segments, study::anatomicalFromSegmentation(
                       *segments, functional,
                       functional ? session.anatomicalFromFunctional() : glm::dmat4(1.0)));
  scene.centre = renderer.centre();
  scene.radius = renderer.radius();
  scene.valueRange = renderer.valueRange();
  return scene;
}

std::vector<std::pair<std::string, glm::dvec3>> segmentCentres(const study::SegmentOverlay& overlay,
                                                               const glm::dmat4& placed) {
  std::vector<std::pair<std::string, glm::dvec3>> centres;
  const Volume& masks = overlay.masks;
  const glm::ivec3 d = masks.dimensions();
  for (int c = 0; c < masks.components(); ++c) {
    glm::dvec3 sum(0.0);
    double count = 0.0;
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i)
          if (masks.value(i, j, k, c) != 0.0) sum += glm::dvec3(i, j, k), count += 1.0;
    if (count == 0.0) continue;
    const glm::dvec3 world = masks.worldFromIndexPoint(sum / count);
    centres.push_back(
        {overlay.names[static_cast<std::size_t>(c)], glm::dvec3(placed * glm::dvec4(world, 1.0))});
  }
  return centres;
}

output::ViewAnnotations paneAnnotations(const ViewerState& state, int pane,
                                        const render::RenderSettings& s,
                                        std::pair<double, double> functionalRange,
                                        const study::SegmentOverlay* segments) {
  output::ViewAnnotations a;
  a.caption = state.caption(pane, s);
  a.glyphLegend = state.glyphLegend(pane, s);
  if (state.paneShowsFunctional(pane)) {
    const Volume& functional = *state.functional();
    a.colourBar = output::ColourBar{s.level - 0.5 * s.window, s.level + 0.5 * s.window,
                                    functional.metadata().unit, s.imageColors,
                                    ViewerState::volumeName(functional, "functional")};
  } else {
    const auto [lo, hi] = state.scene().valueRange;
    a.colourBar = output::colourBarOf(s, state.anatomical(), state.functional(), functionalRange,
                                      windowOrFullRange(s.window, s.level, lo, hi));
  }
  a.segmentLegend = output::segmentLegendOf(s, segments);
  return a;
}

}  // namespace mvw::viewer
