#include "mvw/io/ColorPalettes.h"

#include <vtkDICOMLookupTable.h>
#include <vtkNew.h>

#include "mvw/core/Error.h"

namespace mvw::io {

ColorTable standardColorTable(ColorMap map) {
  const char* code = nullptr;
  switch (map) {
    case ColorMap::Grey:
      return greyTable(false);
    case ColorMap::GreyInverted:
      return greyTable(true);
    case ColorMap::HotIron:
      code = "HOT_IRON";
      break;
    case ColorMap::Pet:
      code = "PET";
      break;
    case ColorMap::HotMetalBlue:
      code = "HOT_METAL_BLUE";
      break;
    case ColorMap::Pet20Step:
      code = "PET_20_STEP";
      break;
    case ColorMap::HotMetal:
      break;
  }
  if (code == nullptr) throw Error("'" + toString(map) + "' is not a DICOM standard palette");
  // vtk-dicom builds the palettes from the standard's definition; its entries match the
  // standard's tabulated palette data (the well-known Color Palette instances) exactly for
  // HOT_IRON and PET_20_STEP and within 1 (PET) and 2 (HOT_METAL_BLUE) of 255 at a few entries.
  vtkNew<vtkDICOMLookupTable> lut;
  lut->BuildStandardPalette(code);
  if (lut->GetNumberOfTableValues() != 256)
    throw Error("vtk-dicom's " + std::string(code) + " palette does not have 256 entries");
  ColorTable t;
  t.map = map;
  const unsigned char* rgba = lut->GetPointer(0);
  for (std::size_t i = 0; i < 256; ++i)
    for (std::size_t c = 0; c < 3; ++c) t.rgb[i][c] = rgba[4 * i + c];
  return t;
}

}  // namespace mvw::io
