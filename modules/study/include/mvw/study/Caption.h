#pragma once
// The one-line caption of a view ("composite  ct-bone  glyphs sized convex"), burned into
// annotated renders by `mvw render` and drawn on the viewer's panes.
#include <string>

#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/Annotations.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {

// A volume's name in readouts, statistics and colour bars, so that two volumes of one modality
// read apart: its modality ("PET" for DICOM's PT) and series description, or its file's name
// without extensions ("MR relCBF", "CT Cranium", "aal"); `role` ("anatomical", "functional")
// where it names neither. At most 24 characters of the description.
std::string volumeName(const Volume& volume, const char* role);

// `shown`: the window the projection or MPR actually used (windowOrFullRange).
std::string viewCaption(const PlannedView& view, const WindowLevel& shown);

// What a glyph view's bumps mean (empty for views without glyphs): the attribute values at the
// window's low end, middle and high end with the bump sizes eqs. (2)-(3) and the minimum size
// give them (dimples below the middle for "both"), or the label classes. unit: the attribute's.
// range: the functional value range, for views without their own window.
render::GlyphLegend glyphLegend(const PlannedView& view, const std::string& unit,
                                std::pair<double, double> range);

}  // namespace mvw::study
