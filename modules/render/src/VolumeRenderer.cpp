#include "mvw/render/VolumeRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <map>
#include <tuple>
#include <utility>

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "BlockGrid.h"
#include "BoxProxy.h"
#include "FunctionalTextures.h"
#include "GlObjects.h"
#include "GlyphIcons.h"
#include "GlyphTextures.h"
#include "RaycastPrograms.h"
#include "RenderTarget.h"
#include "SampleCeiling.h"
#include "SegmentTextures.h"
#include "ShellRenderer.h"
#include "TextureUpload.h"
#include "TransferTable.h"
#include "VolumeTextures.h"
#include "mvw/core/Error.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/Framing.h"

namespace mvw::render {

namespace {

// The members below upload as they are constructed: the context must be current first.
GlContext& madeCurrent(GlContext& context) {
  context.makeCurrent();
  return context;
}

// A folded volume's gradient is always taken on the fly, and one on the fly is never packed.
detail::VolumeLayout layoutOf(const detail::VolumeTextures& volume) {
  if (volume.foldRuns() > 1) return detail::VolumeLayout::FoldedOnTheFly;
  if (volume.gradientSource() == GradientSource::OnTheFly) return detail::VolumeLayout::OnTheFly;
  return volume.packed() ? detail::VolumeLayout::PackedGradient : detail::VolumeLayout::Gradient;
}

}  // namespace

struct VolumeRenderer::Impl {
  GlContext& context;
  detail::VolumeTextures volume;
  FramingSphere framing;
  PatientCrop crop;
  double defaultStep;
  detail::BlockGrid blocks;
  detail::TransferTable transfer;
  detail::FunctionalTextures functional;
  detail::GlyphTextures glyphs;
  detail::SegmentTextures segments;
  detail::RaycastPrograms programs;
  detail::RenderTarget target;
  detail::VertexArray vao;
  detail::SampleCeiling ceiling;
  std::unique_ptr<detail::ShellRenderer> shells;  // made on the first shell-mode frame
  // The view's colour map (RenderSettings::imageColors), uploaded when it changes.
  detail::Texture imageColormap;
  std::optional<ColorTable> imageTable;
  std::unique_ptr<detail::GlyphIcons> icons;  // made on the first legend with icons

  Impl(GlContext& c, const Volume& v, GradientSource gradient)
      : context(madeCurrent(c)),
        volume(v, gradient),
        framing(framingSphere(v)),
        crop(v),
        defaultStep(defaultStepMm(v)),
        blocks(v),
        programs(layoutOf(volume)),
        vao(detail::makeVertexArray()) {}

  Camera cameraFor(const RenderSettings& s) const;
  Image drawShells(const RenderSettings& s, const Camera& camera);
  Image rayCast(const RenderSettings& s, const Camera& camera);
  void setVolumeUniforms(const ShaderProgram& p) const;
  std::pair<glm::dvec3, glm::dvec3> cropFractions(const RenderSettings& s) const;
  std::pair<glm::dvec3, glm::dvec3> rayBox(const RenderSettings& s) const;
  void setRayUniforms(const ShaderProgram& p, const RenderSettings& s, const Camera& camera,
                      double step) const;
  void setShadingUniforms(const ShaderProgram& p, const RenderSettings& s,
                          const Camera& camera) const;
  void setFunctionalUniforms(const ShaderProgram& p, const RenderSettings& s, bool fusion,
                             glm::vec2 window) const;
  void bindTextures(const ShaderProgram& p, GLuint overlayColormap, GLuint blockRange) const;
  void updateImageColormap(const std::optional<ColorTable>& table);
};

void VolumeRenderer::Impl::updateImageColormap(const std::optional<ColorTable>& table) {
  if (!table || (imageTable && imageTable->rgb == table->rgb)) return;
  if (!imageColormap.id()) imageColormap = detail::makeTexture();
  detail::uploadColorTable(imageColormap.id(), *table);
  imageTable = table;
}

// Around the framing sphere. MPR is always orthographic; so are the shells, since the
// paper's transform is affine in z.
Camera VolumeRenderer::Impl::cameraFor(const RenderSettings& s) const {
  CameraSettings settings = s.camera;
  if (s.mode == RenderMode::Mpr || isShellMode(s.mode)) settings.perspective = false;
  return makeCamera(settings, framing.centre, framing.radius, s.size);
}

Image VolumeRenderer::Impl::drawShells(const RenderSettings& s, const Camera& camera) {
  if (!shells)
    shells = std::make_unique<detail::ShellRenderer>(volume.values(), volume.dims(),
                                                     volume.worldFromIndex());
  detail::ShellDraw d;
  d.mode = s.mode == RenderMode::ShellMip   ? detail::ShellMode::Maximum
           : s.mode == RenderMode::ShellSum ? detail::ShellMode::Summation
                                            : detail::ShellMode::Lit;
  d.size = s.size;
  d.camera = camera;
  d.centre = framing.centre;
  d.radius = framing.radius;
  const auto [lo, hi] = volume.range();
  const WindowLevel wl = windowOrFullRange(s.window, lo, hi);
  d.windowLow = wl.level - 0.5 * wl.window;
  d.windowWidth = wl.window;
  d.count = s.shells;
  d.enabled = s.shellEnabled;
  if (s.depthCue.on) d.depthCue = s.depthCue;
  d.light = s.light;
  return shells->draw(d);
}

Image VolumeRenderer::Impl::rayCast(const RenderSettings& s, const Camera& camera) {
  if (s.glyphs.on && !functional.present())
    throw Error("glyph rendering needs a functional volume (the study has none)");
  if (s.glyphs.on && !(s.glyphDiameterMm > 0)) throw Error("glyph diameter must be positive");
  const double step = s.stepMm > 0 ? s.stepMm : defaultStep;

  // What this frame's settings derive: the transfer table and the blocks it leaves visible,
  // and for glyphs the map and the attribute volume (both cached).
  const auto [lo, hi] = volume.transferRange();
  transfer.update(s.transfer, lo, hi, step, volume.referenceStepMm(), s.gradientOpacity.low,
                  s.gradientOpacity.high);
  blocks.updateVisibility(transfer.lut(), lo, hi, s.mode == RenderMode::Composite);
  volume.setLinear(s.linear);
  const glm::vec2 functionalWindow = functional.window(s.functionalWindow);
  if (s.glyphs.on) {
    glyphs.uploadMap(s.glyphMap);
    glyphs.updateBeta(volume, functional, functionalWindow, s.functionalClasses, s.glyphLabels,
                      usesGlyphKinds(s) ? s.glyphs.classKinds : std::vector<GlyphKind>{},
                      usesGlyphKinds(s), programs.beta(), vao.id());
  }

  target.bind(s.size);
  const bool fusion = showsFunctional(s, functional.present());
  const ShaderProgram& p = programs.forMode(s.mode, s, fusion);
  p.use();
  setVolumeUniforms(p);
  setRayUniforms(p, s, camera, step);
  setShadingUniforms(p, s, camera);
  detail::setFeatureUniforms(p, s.mode, detail::RaycastPrograms::variants(s, fusion),
                             {s, camera, step, framing, transfer, glyphs});
  setFunctionalUniforms(p, s, fusion, functionalWindow);
  segments.setUniforms(p, s.mode == RenderMode::Mpr && s.segmentationOutlines);
  if (showsImageColors(s)) updateImageColormap(s.imageColors);
  // The fused projections skip by both volumes' block ranges (BlockGrid::setFunctional), plain
  // MIP by its own with the levels' distances (BlockGrid::prepareMipLevels).
  GLuint blockRange = blocks.minMax();
  if (fusion && isProjectionMode(s.mode)) {
    blockRange = blocks.fusedMinMax();
  } else if (s.mode == RenderMode::Mip) {
    blocks.prepareMipLevels();
    blockRange = blocks.mipRange();
  }
  const glm::vec3 levels = blocks.mipLevels();
  glUniform3f(p.uniform("uMipLevels"), levels.x, levels.y, levels.z);
  bindTextures(p, functional.colormap(s.overlayColors), blockRange);

  glViewport(0, 0, s.size.x, s.size.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(vao.id());
  if (!detail::RaycastPrograms::usesBoxProxy(s.mode)) {
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return target.read();
  }
  // The rays run only where the box's proxy falls; elsewhere the target keeps what a ray that
  // meets nothing writes: the background (the colour map's own where one applies: then the
  // whole viewport is drawn instead) and no depth.
  // Composite: within the crop, only the box of the blocks the transfer function can show
  // (no sample outside it adds anything); none at all leaves the background alone.
  auto [boxMin, boxMax] = rayBox(s);
  std::tie(boxMin, boxMax) = std::pair{glm::min(boxMin, boxMax), glm::max(boxMin, boxMax)};
  if (s.mode == RenderMode::Composite) {
    boxMin = glm::max(boxMin, blocks.visibleBox().first);
    boxMax = glm::min(boxMax, blocks.visibleBox().second);
  }
  const GLfloat background[] = {s.background.r, s.background.g, s.background.b, 1.0f};
  const GLfloat noDepth[] = {-1.0f, 0.0f, 0.0f, 0.0f};
  glClearBufferfv(GL_COLOR, 0, background);
  glClearBufferfv(GL_COLOR, 1, noDepth);
  if (glm::any(glm::greaterThan(boxMin, boxMax))) return target.read();
  detail::BoxProxy proxy = detail::boxProxy(camera, volume.textureFromWorld(), boxMin, boxMax);
  if (showsImageColors(s)) proxy.fullscreen = true;
  const glm::mat4 clipFromTexture(proxy.clipFromTexture);
  glUniformMatrix4fv(p.uniform("uClipFromTexture"), 1, GL_FALSE, glm::value_ptr(clipFromTexture));
  glUniform3f(p.uniform("uProxyMin"), float(proxy.min.x), float(proxy.min.y), float(proxy.min.z));
  glUniform3f(p.uniform("uProxyMax"), float(proxy.max.x), float(proxy.max.y), float(proxy.max.z));
  glUniform1i(p.uniform("uFaces"), proxy.faces);
  glUniform1i(p.uniform("uFullscreen"), proxy.fullscreen ? 1 : 0);
  glEnable(GL_DEPTH_CLAMP);  // faces before the near plane or past the far one still count
  glDrawArrays(GL_TRIANGLES, 0, 36);
  glDisable(GL_DEPTH_CLAMP);
  return target.read();
}

// uVolume (the per-volume struct), the block grid and the transfer table's mapping.
void VolumeRenderer::Impl::setVolumeUniforms(const ShaderProgram& p) const {
  const auto [lo, hi] = volume.transferRange();
  const glm::ivec3 dims = volume.dims();
  const glm::mat4 textureFromWorld(volume.textureFromWorld());
  glUniformMatrix4fv(p.uniform("uVolume.textureFromWorld"), 1, GL_FALSE,
                     glm::value_ptr(textureFromWorld));
  glUniform3f(p.uniform("uVolume.dimensions"), float(dims.x), float(dims.y), float(dims.z));
  glUniform1f(p.uniform("uVolume.referenceStep"), float(volume.referenceStepMm()));
  glUniform2f(p.uniform("uVolume.valueRange"), float(lo), float(hi));
  glUniform1f(p.uniform("uBlockVoxels"), float(detail::BlockGrid::kBlockVoxels));
  // Entry i of the table holds the value lo + i (hi - lo) / (n - 1) and sits at the texel
  // centre (i + 0.5) / n: the column a value is looked up at puts it there, so that linear
  // filtering reads the entries block visibility checked (BlockGrid::updateVisibility).
  const double n = detail::TransferTable::kEntries;
  glUniform2f(p.uniform("uTransferRange"), float((n - 1.0) / (n * (hi - lo))),
              float((0.5 - lo * (n - 1.0) / (hi - lo)) / n));
  const glm::vec2 visible = transfer.visibleValues();
  glUniform2f(p.uniform("uVisibleValues"), visible.x, visible.y);
  volume.setUniforms(p);
}

// The crop as fractions of the patient axes' extent (PatientCrop).
std::pair<glm::dvec3, glm::dvec3> VolumeRenderer::Impl::cropFractions(
    const RenderSettings& s) const {
  if (s.crop.minMm && s.crop.maxMm) return crop.fractionsFromMm(*s.crop.minMm, *s.crop.maxMm);
  return {s.crop.min, s.crop.max};
}

// The box the rays sample, in texture coordinates: along the patient axes the crop; an oblique
// volume's whole box, since it is clipped in world mm instead (PatientCrop::worldBox).
std::pair<glm::dvec3, glm::dvec3> VolumeRenderer::Impl::rayBox(const RenderSettings& s) const {
  if (!crop.axisAligned()) return {glm::dvec3(0.0), glm::dvec3(1.0)};
  const auto [lpsMin, lpsMax] = cropFractions(s);
  return crop.textureBox(lpsMin, lpsMax);
}

// The rays: through which pixels, how far apart their samples, where they may go.
void VolumeRenderer::Impl::setRayUniforms(const ShaderProgram& p, const RenderSettings& s,
                                          const Camera& camera, double step) const {
  const glm::mat4 worldFromClip(camera.worldFromClip);
  glUniformMatrix4fv(p.uniform("uWorldFromClip"), 1, GL_FALSE, glm::value_ptr(worldFromClip));
  glUniform2f(p.uniform("uViewport"), float(s.size.x), float(s.size.y));
  glUniform1f(p.uniform("uStep"), float(step));
  glUniform1i(p.uniform("uMaxSteps"), static_cast<int>(std::ceil(2.0 * framing.radius / step)) + 2);
  glUniform1i(p.uniform("uJitter"), s.jitter ? 1 : 0);
  glUniform1ui(p.uniform("uSeed"), s.seed);
  const auto [cmin, cmax] = rayBox(s);
  // 1e30: no world clip, so axis-aligned renders are unchanged.
  glm::dvec3 wmin(-1e30), wmax(1e30);
  if (!crop.axisAligned()) {
    const auto [lpsMin, lpsMax] = cropFractions(s);
    std::tie(wmin, wmax) = crop.worldBox(lpsMin, lpsMax);
  }
  glUniform3f(p.uniform("uBoxMin"), float(cmin.x), float(cmin.y), float(cmin.z));
  glUniform3f(p.uniform("uBoxMax"), float(cmax.x), float(cmax.y), float(cmax.z));
  glUniform3f(p.uniform("uWorldBoxMin"), float(wmin.x), float(wmin.y), float(wmin.z));
  glUniform3f(p.uniform("uWorldBoxMax"), float(wmax.x), float(wmax.y), float(wmax.z));
  const glm::vec3 planeCentre(framing.centre + camera.forward * s.planeOffsetMm);
  glUniform3f(p.uniform("uPlaneCentre"), planeCentre.x, planeCentre.y, planeCentre.z);
  glUniform1f(p.uniform("uSlab"), float(std::max(0.0, s.slabMm)));
}

// What a sample looks like: light, window, isovalue, background (the features' own uniforms:
// RaycastFeatures.cpp).
void VolumeRenderer::Impl::setShadingUniforms(const ShaderProgram& p, const RenderSettings& s,
                                              const Camera& camera) const {
  glUniform3f(p.uniform("uBackground"), s.background.r, s.background.g, s.background.b);
  glUniform4f(p.uniform("uLight"), s.light.x, s.light.y, s.light.z, s.light.w);
  const glm::vec3 lightDir(glm::normalize(-camera.forward + s.lightOffset.x * camera.right +
                                          s.lightOffset.y * camera.up));
  glUniform3f(p.uniform("uLightDir"), lightDir.x, lightDir.y, lightDir.z);
  glUniform1i(p.uniform("uHeadlight"), s.lightOffset == glm::dvec2(0.0) ? 1 : 0);
  glUniform1i(p.uniform("uShading"), s.shading ? 1 : 0);
  const auto [lo, hi] = volume.transferRange();
  const WindowLevel wl = windowOrFullRange(s.window, lo, hi);
  glUniform2f(p.uniform("uWindowLevel"), float(wl.window), float(wl.level));
  glUniform1f(p.uniform("uIsoValue"), float(s.iso));
  glUniform4f(p.uniform("uIsoColor"), s.isoColor.r, s.isoColor.g, s.isoColor.b, s.isoColor.a);
}

void VolumeRenderer::Impl::setFunctionalUniforms(const ShaderProgram& p, const RenderSettings& s,
                                                 bool fusion, glm::vec2 window) const {
  functional.setUniforms(p, window, s.functionalClasses);
  glUniform1i(p.uniform("uHasFunctional"), fusion ? 1 : 0);
  glUniform1f(p.uniform("uOverlayOpacity"), float(s.overlay.opacity));
  glUniform1f(p.uniform("uOverlayThreshold"), float(s.overlay.threshold));
}

// Every sampler on its own unit, also those the program does not use (uniform -1 is ignored).
void VolumeRenderer::Impl::bindTextures(const ShaderProgram& p, GLuint overlayColormap,
                                        GLuint blockRange) const {
  const struct {
    const char* name;
    GLenum target;
    GLuint id;
  } units[] = {{"uIntensity", GL_TEXTURE_3D, volume.intensity()},
               {"uGradient", GL_TEXTURE_3D, volume.gradient()},
               {"uAttribute", GL_TEXTURE_3D, volume.attribute()},
               {"uBlocks", GL_TEXTURE_3D, blocks.visibility()},
               {"uTransfer", GL_TEXTURE_2D, transfer.texture()},
               {"uBlockRange", GL_TEXTURE_3D, blockRange},
               {"uFunctional", GL_TEXTURE_3D, functional.texture()},
               {"uColormap", GL_TEXTURE_1D, overlayColormap},
               {"uGlyphCells", GL_TEXTURE_3D, glyphs.cells()},
               {"uImageColormap", GL_TEXTURE_1D, imageColormap.id()},
               {"uSegments", GL_TEXTURE_3D, segments.texture()}};
  for (int u = 0; u < static_cast<int>(std::size(units)); ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(units[u].target, units[u].id);
    glUniform1i(p.uniform(units[u].name), u);
  }
  glActiveTexture(GL_TEXTURE0);
}

bool usesGlyphKinds(const RenderSettings& s) {
  if (s.glyphLabels.empty() && !s.glyphs.classKinds.empty()) return true;
  for (const LabelGlyph& l : s.glyphLabels)
    if (l.kind != GlyphKind::Bumps && l.kind != GlyphKind::Dimples) return true;
  return false;
}

bool cropsVolume(const RenderSettings& s) {
  if (s.crop.minMm && s.crop.maxMm) return true;
  return s.crop.min != glm::dvec3(0.0) || s.crop.max != glm::dvec3(1.0);
}

bool showsAnatomyOnCutFace(const RenderSettings& s) {
  return hasCutFace(s.mode) && s.cutFace == CutFace::Anatomy && cropsVolume(s);
}

bool showsImageColors(const RenderSettings& s) { return s.imageColors && takesImageColors(s.mode); }

bool showsFusion(const RenderSettings& s, bool hasFunctional) {
  return hasFunctional && s.overlay.fusion && takesFusion(s.mode);
}

bool showsFunctional(const RenderSettings& s, bool hasFunctional) {
  return s.mode == RenderMode::Mpr ? hasFunctional && s.overlay.mpr : showsFusion(s, hasFunctional);
}

VolumeRenderer::VolumeRenderer(GlContext& context, const Volume& volume, GradientSource gradient)
    : impl_(std::make_unique<Impl>(context, volume, gradient)) {}

VolumeRenderer::~VolumeRenderer() = default;

RenderedFrame VolumeRenderer::render(const RenderSettings& s) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  if (s.size.x <= 0 || s.size.y <= 0 || s.size.x > 8192 || s.size.y > 8192)
    throw Error("image size must be 1..8192 pixels a side");
  const auto start = std::chrono::steady_clock::now();
  RenderedFrame frame;
  frame.camera = m.cameraFor(s);
  frame.image = isShellMode(s.mode) ? m.drawShells(s, frame.camera) : m.rayCast(s, frame.camera);
  frame.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

std::pair<double, double> VolumeRenderer::valueRange() const { return impl_->volume.range(); }

GradientSource VolumeRenderer::gradientSource() const { return impl_->volume.gradientSource(); }
int VolumeRenderer::textureRuns() const { return impl_->volume.foldRuns(); }

const char* toString(GradientSource source) {
  switch (source) {
    case GradientSource::Texture:
      return "texture";
    case GradientSource::OnTheFly:
      return "shader";
    case GradientSource::Auto:
      break;
  }
  return "auto";
}

GradientSource parseGradientSource(const std::string& name) {
  for (GradientSource g : {GradientSource::Auto, GradientSource::Texture, GradientSource::OnTheFly})
    if (name == toString(g)) return g;
  throw Error("unknown gradient source '" + name + "' (auto, texture or shader)");
}

glm::dvec3 VolumeRenderer::centre() const { return impl_->framing.centre; }

double VolumeRenderer::radius() const { return impl_->framing.radius; }

FramingSphere VolumeRenderer::framing() const { return impl_->framing; }

void VolumeRenderer::renderGlyphIcons(const RenderSettings& view, GlyphLegend& legend, int pixels) {
  Impl& m = *impl_;
  if (!m.icons) m.icons = std::make_unique<detail::GlyphIcons>();
  m.icons->fill(m.context, view, legend, pixels);
}

void VolumeRenderer::setFunctional(const Volume& functional,
                                   const glm::dmat4& anatomicalFromFunctional) {
  impl_->context.makeCurrent();
  impl_->functional.set(functional, anatomicalFromFunctional);
  impl_->blocks.setFunctional(functional, glm::inverse(functional.worldFromIndex()) *
                                              glm::inverse(anatomicalFromFunctional) *
                                              impl_->volume.worldFromIndex());
}

void VolumeRenderer::setSegmentation(const Volume& masks, const std::vector<glm::vec3>& colours,
                                     const glm::dmat4& anatomicalFromSegmentation) {
  impl_->context.makeCurrent();
  impl_->segments.set(masks, colours, anatomicalFromSegmentation);
}

double VolumeRenderer::sampleCeiling(glm::ivec2 size, int samples, int rounds) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  m.volume.setLinear(true);
  m.target.bind(size);
  const double perSecond =
      m.ceiling.samplesPerSecond(m.volume.intensity(), m.vao.id(), size, samples, rounds);
  m.target.read();  // unbinds it, as a frame does
  return perSecond;
}

double VolumeRenderer::nominalSamples(const RenderSettings& s) const {
  const Impl& m = *impl_;
  const auto [a, b] = m.rayBox(s);
  return detail::nominalSamples(m.cameraFor(s), s.size, m.volume.textureFromWorld(), glm::min(a, b),
                                glm::max(a, b), s.stepMm > 0 ? s.stepMm : m.defaultStep);
}

bool VolumeRenderer::hasFunctional() const { return impl_->functional.present(); }

std::pair<double, double> VolumeRenderer::functionalRange() const {
  return impl_->functional.range();
}

}  // namespace mvw::render
