#pragma once
// The colour maps a reader chooses for a view's image (MIP, MinIP, average, MPR) and for the
// functional overlay: grey, inverted grey (black on white, the usual MIP reading display),
// the DICOM standard palettes (PS3.6 Annex B: Hot Iron, PET, Hot Metal Blue, PET 20 Step),
// and mvw's own hot metal (the pet-hot-metal transfer preset's colours, the overlay's
// default). A ColorTable is the map as 256 RGB entries, index 0 for the lowest value; io fills
// the standard palettes (vtk-dicom), so render stays free of VTK.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mvw/core/RenderMode.h"

namespace mvw {

enum class ColorMap { Grey, GreyInverted, HotIron, Pet, HotMetalBlue, Pet20Step, HotMetal };

// Config and command-line names: grey, grey-inverted, hot-iron, pet, hot-metal-blue,
// pet-20-step, hot-metal.
std::optional<ColorMap> parseColorMap(const std::string& name);
std::string toString(ColorMap map);
std::vector<std::string> colorMapNames();

struct ColorTable {
  ColorMap map = ColorMap::Grey;
  std::array<std::array<std::uint8_t, 3>, 256> rgb{};
};

// The modes whose image a colour map colours: MIP (also depth-cued), MinIP, average, MPR.
bool takesImageColors(RenderMode mode);

// The grey ramps (0 -> black, 255 -> white, or the reverse), no library needed.
ColorTable greyTable(bool inverted);

}  // namespace mvw
