#pragma once
// The DICOM standard colour palettes (PS3.6 Annex B: HOT_IRON, PET, HOT_METAL_BLUE,
// PET_20_STEP) as 256-entry RGB tables, built by vtk-dicom (vtkDICOMLookupTable), plus the
// grey ramps. mvw's own hot metal is the renderer's (render::hotMetalTable()).
#include "mvw/core/ColorMap.h"

namespace mvw::io {

// Grey, grey-inverted and the four standard palettes; throws mvw::Error for ColorMap::HotMetal
// (not a DICOM palette).
ColorTable standardColorTable(ColorMap map);

}  // namespace mvw::io
