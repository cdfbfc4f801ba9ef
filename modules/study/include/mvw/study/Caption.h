#pragma once
// The one-line caption of a view ("composite  ct-bone  glyphs sized convex"), burned into
// annotated renders by `mvw render` and drawn on the viewer's panes.
#include <string>

#include "mvw/core/WindowLevel.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {

// `shown`: the window the projection or MPR actually used (windowOrFullRange).
std::string viewCaption(const PlannedView& view, const WindowLevel& shown);

}  // namespace mvw::study
