#include "mvw/viewer/OpenedStudy.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/ModalityDefaults.h"
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
    a.colourBar =
        output::ColourBar{s.window.level - 0.5 * s.window.window,
                          s.window.level + 0.5 * s.window.window, functional.metadata().unit,
                          s.imageColors, ViewerState::volumeName(functional, "functional")};
  } else {
    const auto [lo, hi] = state.scene().valueRange;
    const WindowLevel shown = windowOrFullRange(s.window, lo, hi);
    a.colourBar =
        output::colourBarOf(s, state.anatomical(), state.functional(), functionalRange, shown);
    // Every pane that maps values to colours carries its scale (a reader reads a grey MPR's
    // values off it as much as a coloured one's); `mvw render` draws bars for colour maps only,
    // its images unchanged.
    if (!a.colourBar && takesImageColors(s.mode))
      a.colourBar =
          output::ColourBar{shown.level - 0.5 * shown.window, shown.level + 0.5 * shown.window,
                            state.anatomical().metadata().unit, greyTable(false),
                            ViewerState::volumeName(state.anatomical(), "anatomical")};
  }
  // A PET without SUV: its scale says so (the caption says why).
  const bool functionalBar =
      state.paneShowsFunctional(pane) || render::showsFunctional(s, state.functional() != nullptr);
  const Volume& barVolume = functionalBar ? *state.functional() : state.anatomical();
  if (a.colourBar && !study::noSuvNote(barVolume).empty()) a.colourBar->unit += ", no SUV";
  a.segmentLegend = output::segmentLegendOf(s, segments);
  return a;
}

void writePaneReport(const ViewerState& state, const std::filesystem::path& file) {
  nlohmann::json panes = nlohmann::json::array();
  for (int pane = 0; pane < kPaneCount; ++pane) {
    const render::RenderSettings s = state.renderSettings(pane);
    const output::ViewAnnotations a =
        paneAnnotations(state, pane, s, state.scene().functionalRange, nullptr);
    const auto [lo, hi] = state.scene().valueRange;
    const WindowLevel w = windowOrFullRange(s.window, lo, hi);
    nlohmann::json bar = nullptr;
    if (a.colourBar)
      bar = {{"low", a.colourBar->low},
             {"high", a.colourBar->high},
             {"unit", a.colourBar->unit},
             {"title", a.colourBar->title},
             {"colormap", a.colourBar->colors ? toString(a.colourBar->colors->map) : "hot-metal"}};
    panes.push_back({{"pane", ViewerState::paneName(pane)},
                     {"title", state.paneTitle(pane)},
                     {"mode", toString(s.mode)},
                     {"window", {w.level - 0.5 * w.window, w.level + 0.5 * w.window}},
                     {"colour_bar", bar},
                     {"caption", a.caption}});
  }
  // The panel's readout: at the cursor (the script's hover), else at the crosshair.
  const auto cursor = state.cursor();
  const nlohmann::json report = {
      {"panes", panes}, {"readout", state.readout(cursor ? cursor->second : state.crosshair())}};
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << report.dump(2) << "\n";
  if (!out) throw InputError(file, "cannot write the pane report");
}

}  // namespace mvw::viewer
