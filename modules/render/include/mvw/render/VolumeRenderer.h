#pragma once
// GLSL ray casting of one volume in LPS world space with its full geometry (anisotropic
// spacing, direction matrix). Modes: composite DVR (1D transfer function, Phong shading),
// isosurface (bisection + Phong), MIP, MinIP, average intensity. The same shaders serve the
// headless (OSMesa) and the windowed context.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Camera.h"
#include "mvw/render/Framing.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/RenderSettings.h"

namespace mvw::render {

// Where shading takes the anatomy's gradient from. Texture: precomputed on the CPU (Sobel,
// RGBA16F: 8 bytes a voxel on the GL), one sample per shaded step, the fastest on a software
// rasteriser. OnTheFly: central differences of the intensity in the shaders (six more samples
// per shaded step), no memory at all: what a clinical-size volume needs. Auto: the texture
// while it stays within kGradientTextureBudgetBytes (a 512 x 512 x 256 volume), else on the fly.
enum class GradientSource { Auto, Texture, OnTheFly };
inline constexpr std::size_t kGradientTextureBytesPerVoxel = 8;
inline constexpr std::size_t kGradientTextureBudgetBytes = std::size_t(512) << 20;
// "auto", "texture", "shader"; parseGradientSource throws mvw::Error naming the choices.
const char* toString(GradientSource source);
GradientSource parseGradientSource(const std::string& name);

// One render: the image, how long it took, and the camera it was seen through.
struct RenderedFrame {
  Image image;  // with depth: the ray distance (mm) of the reported sample, -1 for none
  double milliseconds = 0.0;
  Camera camera;
};

class VolumeRenderer {
 public:
  // Uploads the volume (first component), its gradient (unless taken on the fly) and its
  // block min/max grid; keeps no reference to `volume`. The context must be current. Throws
  // mvw::Error if the GL cannot hold the volume.
  VolumeRenderer(GlContext& context, const Volume& volume,
                 GradientSource gradient = GradientSource::Auto);
  ~VolumeRenderer();
  VolumeRenderer(const VolumeRenderer&) = delete;
  VolumeRenderer& operator=(const VolumeRenderer&) = delete;

  RenderedFrame render(const RenderSettings& settings);
  std::pair<double, double> valueRange() const;
  // Texture or OnTheFly: what Auto chose for this volume.
  GradientSource gradientSource() const;
  // 1, or how many runs of slices the volume was folded into because it has more slices than
  // the GL's largest 3D texture (side by side in one texture; the gradient then on the fly).
  int textureRuns() const;
  // The sphere the camera frames: framingSphere(volume), the centre of the voxel box and half
  // its diagonal (mm).
  FramingSphere framing() const;
  glm::dvec3 centre() const;
  double radius() const;

  // The sampling ceiling (issue 53): trilinear samples per second of the volume's own
  // intensity texture with a trivial shader (a fetch and an add per sample), `samples` per
  // pixel over `size` pixels, the fastest of `rounds` draws.
  double sampleCeiling(glm::ivec2 size, int samples, int rounds = 3);
  // The samples a frame of `settings` takes without skipping: each ray's length in the box it
  // samples (the crop) over the step. A mode's samples per second against the ceiling.
  double nominalSamples(const RenderSettings& settings) const;

  // A functional volume on its own grid (component 0), placed by the registration:
  // anatomicalFromFunctional maps functional world points (LPS mm) to anatomical ones.
  void setFunctional(const Volume& functional, const glm::dmat4& anatomicalFromFunctional);
  bool hasFunctional() const;
  // Segment masks (one component per segment, non-zero inside; the first 16 are drawn) on
  // their own grid, outlined on MPR views in `colours` (sRGB 0..1, one per segment);
  // anatomicalFromSegmentation maps segmentation world points to anatomical ones.
  void setSegmentation(const Volume& masks, const std::vector<glm::vec3>& colours,
                       const glm::dmat4& anatomicalFromSegmentation);
  std::pair<double, double> functionalRange() const;

  // The glyph legend's icons (issue 40): every entry with a value gets its glyph as `view`'s
  // glyph shading draws it, on a plane through one glyph's centre facing the camera, with the
  // view's light, colours, map and attribute mapping (pixels square).
  void renderGlyphIcons(const RenderSettings& view, GlyphLegend& legend, int pixels = 64);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mvw::render
