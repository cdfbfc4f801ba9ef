#pragma once
// render.json: what `mvw render` asked, what the defaults chose and what it showed, per view
// and for the study (mvw validate's report reads it).
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvw/core/WindowLevel.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::output {

// The image checksum render.json records (FNV-1a, 64 bits, as 16 hex digits).
std::string fnv1a(const std::vector<std::uint8_t>& bytes);

// One view's entry: `shown` the window it used, overlayShown whether it shows the functional
// volume. A note (an empty isosurface, fusion a mode cannot show) is also said on `log`.
nlohmann::json viewRecord(const study::PlannedView& view, const study::Session& session,
                          const render::VolumeRenderer& renderer, const WindowLevel& shown,
                          bool overlayShown, const render::RenderedFrame& frame, std::ostream& log);

// The study-wide part: the sources, what the readers decided (units, reorderings, the frame a
// 4D volume contributes), the placement, the GL that rendered; "views" empty.
nlohmann::json studyRecord(const study::Session& session, const render::VolumeRenderer& renderer,
                           const render::GlContext& context);

}  // namespace mvw::output
