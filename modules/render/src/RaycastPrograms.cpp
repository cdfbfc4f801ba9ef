#include "RaycastPrograms.h"

#include <set>
#include <utility>

namespace mvw::render::detail {

namespace {

RaycastSource betaSource() { return {"fullscreen.vert.glsl", "beta.frag.glsl", {}, {}}; }

// A projection's accumulator: what its samples make of the ray (raycast/accumulate-*.glsl).
const char* accumulatorOf(RenderMode mode) {
  switch (mode) {
    case RenderMode::Mip:
      return "raycast/accumulate-mip.glsl";
    case RenderMode::MinIp:
      return "raycast/accumulate-minip.glsl";
    case RenderMode::Average:
      return "raycast/accumulate-average.glsl";
    default:
      return nullptr;
  }
}

const char* fragmentOf(RenderMode mode) {
  switch (mode) {
    case RenderMode::Composite:
      return "composite.frag.glsl";
    case RenderMode::Isosurface:
      return "isosurface.frag.glsl";
    case RenderMode::Mpr:
      return "mpr.frag.glsl";
    default:
      return "projection.frag.glsl";  // the shell modes are drawn by detail::ShellRenderer
  }
}

// How the layout (VolumeLayout) reaches the shaders (raycast/common.glsl).
void addLayoutDefines(RenderMode mode, VolumeLayout layout, const RaycastVariants& v,
                      std::vector<std::string>& defines) {
  const bool shaded = hasCutFace(mode);  // composite and isosurface read the gradient
  if (layout == VolumeLayout::FoldedOnTheFly) defines.push_back("MVW_FOLDED 1");
  if (shaded && (layout == VolumeLayout::OnTheFly || layout == VolumeLayout::FoldedOnTheFly))
    defines.push_back("MVW_GRADIENT_ON_THE_FLY 1");
  if (shaded && layout == VolumeLayout::PackedGradient) {
    defines.push_back("MVW_PACKED_GRADIENT 1");
    // The packed texture is always trilinear: nearest-neighbour values keep the intensity's.
    if (mode == RenderMode::Composite && !v.on(RaycastFeature::Nearest))
      defines.push_back("MVW_PACKED_VALUE 1");
  }
}

}  // namespace

const ShaderProgram& RaycastPrograms::forMode(RenderMode mode, const RenderSettings& s,
                                              bool fusion) {
  const RaycastSource src = source(mode, layout_, variants(s, fusion));
  std::string key = toString(mode);
  for (const auto& d : src.defines) key += "+" + d;
  return cached(key, src);
}

const ShaderProgram& RaycastPrograms::beta() { return cached("beta", betaSource()); }

bool RaycastPrograms::usesBoxProxy(RenderMode mode) { return mode != RenderMode::Mpr; }

RaycastVariants RaycastPrograms::variants(const RenderSettings& s, bool fusion) {
  RaycastVariants v;
  for (const RaycastFeatureSpec& f : raycastFeatures()) v.set(f.id, f.valueFor(s, fusion));
  return v;
}

RaycastSource RaycastPrograms::source(RenderMode mode, VolumeLayout layout,
                                      const RaycastVariants& v) {
  RaycastSource out;
  out.vertex = usesBoxProxy(mode) ? "box.vert.glsl" : "fullscreen.vert.glsl";
  out.fragment = fragmentOf(mode);
  if (const char* accumulator = accumulatorOf(mode)) out.includes.push_back(accumulator);
  for (const RaycastFeatureSpec& f : raycastFeatures()) {
    if (!featureCounts(f, mode, v)) continue;
    if (const char* define = f.defines[static_cast<std::size_t>(v[f.id])])
      out.defines.push_back(define);
    if (f.includes)
      for (const char* include : f.includes(mode)) out.includes.push_back(include);
  }
  addLayoutDefines(mode, layout, v, out.defines);
  return out;
}

std::vector<RaycastSource> RaycastPrograms::every() {
  std::vector<RaycastSource> out;
  std::set<std::vector<std::string>> seen;
  auto add = [&](RaycastSource s) {
    std::vector<std::string> key = s.defines;
    key.insert(key.end(), s.includes.begin(), s.includes.end());
    key.push_back(s.vertex);
    key.push_back(s.fragment);
    if (seen.insert(std::move(key)).second) out.push_back(std::move(s));
  };
  const auto& features = raycastFeatures();
  // Through the modes' names, so that a mode added later is among them too.
  for (const std::string& name : renderModeNames()) {
    const RenderMode mode = *parseRenderMode(name);
    if (isShellMode(mode)) continue;
    for (int layout = 0; layout < static_cast<int>(VolumeLayout::Count); ++layout) {
      // Each feature's values in turn, the first feature counting fastest.
      RaycastVariants v;
      for (;;) {
        add(source(mode, static_cast<VolumeLayout>(layout), v));
        std::size_t f = 0;
        for (; f < features.size(); ++f) {
          const int next = v[features[f].id] + 1;
          v.set(features[f].id, next < features[f].values ? next : 0);
          if (next < features[f].values) break;
        }
        if (f == features.size()) break;  // every combination made
      }
    }
  }
  add(betaSource());
  return out;
}

const ShaderProgram& RaycastPrograms::cached(const std::string& key, const RaycastSource& source) {
  auto it = programs_.find(key);
  if (it == programs_.end())
    it = programs_
             .emplace(key, ShaderProgram(source.vertex, source.fragment, source.defines,
                                         source.includes))
             .first;
  return it->second;
}

}  // namespace mvw::render::detail
