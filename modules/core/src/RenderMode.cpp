#include "mvw/core/RenderMode.h"

#include <array>
#include <utility>

namespace mvw {

namespace {

constexpr std::array<std::pair<RenderMode, const char*>, 9> kModeNames = {{
    {RenderMode::Composite, "composite"},
    {RenderMode::Isosurface, "isosurface"},
    {RenderMode::Mip, "mip"},
    {RenderMode::MinIp, "minip"},
    {RenderMode::Average, "average"},
    {RenderMode::Mpr, "mpr"},
    {RenderMode::ShellMip, "shells-mip"},
    {RenderMode::ShellSum, "shells-sum"},
    {RenderMode::ShellLit, "shells-lit"},
}};

}  // namespace

std::optional<RenderMode> parseRenderMode(const std::string& name) {
  for (const auto& [mode, n] : kModeNames)
    if (n == name) return mode;
  return std::nullopt;
}

std::string toString(RenderMode mode) {
  for (const auto& [m, n] : kModeNames)
    if (m == mode) return n;
  return "?";
}

bool isShellMode(RenderMode mode) {
  return mode == RenderMode::ShellMip || mode == RenderMode::ShellSum ||
         mode == RenderMode::ShellLit;
}

bool isProjectionMode(RenderMode mode) {
  return mode == RenderMode::Mip || mode == RenderMode::MinIp || mode == RenderMode::Average;
}

bool takesFusion(RenderMode mode) {
  return mode == RenderMode::Composite || mode == RenderMode::Isosurface || isProjectionMode(mode);
}

bool takesFusionMean(RenderMode mode) {
  return mode == RenderMode::MinIp || mode == RenderMode::Average;
}

bool hasCutFace(RenderMode mode) {
  return mode == RenderMode::Composite || mode == RenderMode::Isosurface;
}

std::vector<std::string> renderModeNames() {
  std::vector<std::string> out;
  for (const auto& [m, n] : kModeNames) out.push_back(n);
  return out;
}

}  // namespace mvw
