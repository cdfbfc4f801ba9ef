#pragma once
// A study opened in the viewer, as the window loop hands it to the state and the panes: the
// scene its renderer reports, the segments' centres, and each pane's annotations (drawn by
// `mvw render`'s painter, output::drawAnnotations).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/output/ViewAnnotations.h"
#include "mvw/render/RenderSettings.h"
#include "mvw/study/SegmentOverlay.h"
#include "mvw/study/Session.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::render {
class VolumeRenderer;
}

namespace mvw::viewer {

// The scene of a loaded study whose anatomy `renderer` holds (Session::attach): the framing and
// ranges the renderer reports, how the functional volume was placed, the segments' centres.
ViewerScene studyScene(const study::Session& session, const render::VolumeRenderer& renderer);

// Each segment's centre (the mean of its voxel centres), placed by `anatomicalFromSegmentation`
// (where the outlines put it), by the segment's name; a segment without voxels has none.
std::vector<std::pair<std::string, glm::dvec3>> segmentCentres(const study::SegmentOverlay& overlay,
                                                               const glm::dmat4& placed);

// The annotations of a pane rendered with `s`: its caption and glyph legend, its colour bar
// (the PET/CT layout's MIP: the functional volume's own window; else as `mvw render` has it,
// with the renderer's functional range) and the legend of the study's segments (null: none).
output::ViewAnnotations paneAnnotations(const ViewerState& state, int pane,
                                        const render::RenderSettings& s,
                                        std::pair<double, double> functionalRange,
                                        const study::SegmentOverlay* segments);

// Every pane as the window draws it (the script's pane-report), JSON: {"panes": [{"pane",
// "title", "mode", "window": [low, high], "colour_bar": {"low", "high", "unit", "title",
// "colormap"} or null, "caption"}, ...], "readout": the panel's readout at the cursor (else at
// the crosshair)}, so that a test reads what a reader sees without reading pixels. Throws
// InputError naming the file where it cannot be written.
void writePaneReport(const ViewerState& state, const std::filesystem::path& file);

}  // namespace mvw::viewer
