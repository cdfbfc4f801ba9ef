#include "mvw/core/ColorMap.h"

#include <utility>

namespace mvw {

namespace {

constexpr std::array<std::pair<ColorMap, const char*>, 7> kNames = {{
    {ColorMap::Grey, "grey"},
    {ColorMap::GreyInverted, "grey-inverted"},
    {ColorMap::HotIron, "hot-iron"},
    {ColorMap::Pet, "pet"},
    {ColorMap::HotMetalBlue, "hot-metal-blue"},
    {ColorMap::Pet20Step, "pet-20-step"},
    {ColorMap::HotMetal, "hot-metal"},
}};

}  // namespace

std::optional<ColorMap> parseColorMap(const std::string& name) {
  for (const auto& [map, n] : kNames)
    if (n == name) return map;
  return std::nullopt;
}

std::string toString(ColorMap map) {
  for (const auto& [m, n] : kNames)
    if (m == map) return n;
  return "?";
}

std::vector<std::string> colorMapNames() {
  std::vector<std::string> names;
  for (const auto& entry : kNames) names.emplace_back(entry.second);
  return names;
}

bool takesImageColors(RenderMode mode) { return isProjectionMode(mode) || mode == RenderMode::Mpr; }

ColorTable greyTable(bool inverted) {
  ColorTable t;
  t.map = inverted ? ColorMap::GreyInverted : ColorMap::Grey;
  for (int i = 0; i < 256; ++i) {
    const auto g = static_cast<std::uint8_t>(inverted ? 255 - i : i);
    t.rgb[static_cast<std::size_t>(i)] = {g, g, g};
  }
  return t;
}

}  // namespace mvw
