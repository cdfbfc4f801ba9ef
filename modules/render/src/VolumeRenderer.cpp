#include "mvw/render/VolumeRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "GlObjects.h"
#include "ShellRenderer.h"
#include "mvw/core/Error.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render {

namespace {

constexpr int kBlock = 8;

const std::map<RenderMode, std::string> kModeNames = {{RenderMode::Composite, "composite"},
                                                      {RenderMode::Isosurface, "isosurface"},
                                                      {RenderMode::Mip, "mip"},
                                                      {RenderMode::MinIp, "minip"},
                                                      {RenderMode::Average, "average"},
                                                      {RenderMode::Mpr, "mpr"},
                                                      {RenderMode::ShellMip, "shells-mip"},
                                                      {RenderMode::ShellSum, "shells-sum"},
                                                      {RenderMode::ShellLit, "shells-lit"}};

// Values of component 0 as float, in the volume's physical unit.
std::vector<float> valuesOf(const Volume& v) {
  std::vector<float> out(v.voxelCount());
  const int nc = v.components();
  dispatchScalar(v.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* p = reinterpret_cast<const T*>(v.data());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(p[i * nc]);
    return 0;
  });
  return out;
}

// Central differences on the voxel grid with physical spacing (one-sided at the border),
// turned into world (LPS) directions with the direction matrix: the seed's gradient volume.
// The fourth component carries the functional attribute for glyph shading (see
// VolumeRenderer::Impl::updateBeta); shaders take the magnitude from the vector.
std::vector<float> gradientOf(const std::vector<float>& v, glm::ivec3 d, const glm::dvec3& spacing,
                              const glm::dmat3& direction) {
  std::vector<float> g(v.size() * 4);
  auto at = [&](int i, int j, int k) { return v[(static_cast<std::size_t>(k) * d.y + j) * d.x + i]; };
  auto work = [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          // Central differences along each axis, averaged over the 3 x 3 neighbours across it
          // with weights 1 2 1 (Sobel): 8-bit data then shade without contour terraces.
          glm::dvec3 local(0.0);
          const glm::ivec3 c(i, j, k);
          for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, e = (a + 2) % 3;
            glm::ivec3 lo = c, hi = c;
            lo[a] = std::max(c[a] - 1, 0);
            hi[a] = std::min(c[a] + 1, d[a] - 1);
            if (hi[a] == lo[a]) continue;
            double sum = 0.0, weight = 0.0;
            for (int db = -1; db <= 1; ++db)
              for (int de = -1; de <= 1; ++de) {
                glm::ivec3 p = lo, q = hi;
                p[b] = q[b] = std::clamp(c[b] + db, 0, d[b] - 1);
                p[e] = q[e] = std::clamp(c[e] + de, 0, d[e] - 1);
                const double w = (db == 0 ? 2.0 : 1.0) * (de == 0 ? 2.0 : 1.0);
                sum += w * (at(q.x, q.y, q.z) - at(p.x, p.y, p.z));
                weight += w;
              }
            local[a] = sum / weight / ((hi[a] - lo[a]) * spacing[a]);
          }
          const glm::dvec3 w = direction * local;
          float* out = &g[((static_cast<std::size_t>(k) * d.y + j) * d.x + i) * 4];
          out[0] = static_cast<float>(w.x);
          out[1] = static_cast<float>(w.y);
          out[2] = static_cast<float>(w.z);
          out[3] = 0.0f;  // the functional attribute (glyph beta), written on the GPU when needed
        }
  };
  const int half = d.z / 2;
  std::thread other(work, 0, half);
  work(half, d.z);
  other.join();
  return g;
}

void setSampling(GLuint tex, GLenum target, bool linear) {
  glBindTexture(target, tex);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
}

void checkGl(const char* what);

// A 3D float texture, clamped at the edges: the volume, its gradient, the functional volume.
detail::Texture upload3D(glm::ivec3 d, GLint internalFormat, GLenum format, const float* data, bool linear,
                         const char* what) {
  detail::Texture tex = detail::makeTexture();
  glBindTexture(GL_TEXTURE_3D, tex.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, internalFormat, d.x, d.y, d.z, 0, format, GL_FLOAT, data);
  checkGl(what);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  setSampling(tex.id(), GL_TEXTURE_3D, linear);
  return tex;
}

void checkGl(const char* what) {
  const GLenum e = glGetError();
  if (e == GL_OUT_OF_MEMORY) throw Error(std::string(what) + ": the GL implementation is out of memory for this volume");
  if (e != GL_NO_ERROR) throw Error(std::string(what) + ": GL error 0x" + [&] {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%x", e);
    return std::string(buf);
  }());
}

}  // namespace

std::optional<RenderMode> parseRenderMode(const std::string& name) {
  for (const auto& [mode, n] : kModeNames)
    if (n == name) return mode;
  return std::nullopt;
}

std::string toString(RenderMode mode) { return kModeNames.at(mode); }

struct VolumeRenderer::Impl {
  GlContext& context;
  glm::ivec3 dims;
  glm::dmat4 worldFromIndex;
  glm::dvec3 spacing;
  std::pair<double, double> range;
  glm::ivec3 blockCount;
  std::vector<glm::vec2> blockMinMax;
  detail::Texture intensity, gradient, blocks, blockRange, transfer;
  detail::Texture functional, colormap;
  std::uint64_t functionalGeneration = 0;  // counts setFunctional calls
  // The glyph map as the shaders read it: cell grid + centres (uploaded for glyphMapSettings).
  detail::Texture glyphCells;
  detail::Buffer glyphCentres;
  GlyphMapSettings glyphMapSettings{0, 0, 0.0, 0};
  double glyphRadius = 0.0;
  // What the gradient texture's alpha holds: the functional attribute through this mapping.
  struct BetaKey {
    std::uint64_t generation;
    float low, high;
    int classes;
    bool operator==(const BetaKey&) const = default;
  };
  std::optional<BetaKey> betaKey;
  glm::dmat4 functionalTextureFromAnatomicalWorld{1.0};
  std::pair<double, double> functionalRange{0.0, 1.0};
  detail::VertexArray vao;
  std::map<std::string, ShaderProgram> programs;
  std::vector<float> values;  // kept for the shell modes' surface extraction
  std::unique_ptr<detail::ShellRenderer> shells;

  explicit Impl(GlContext& c) : context(c) {}

  ShaderProgram& cachedProgram(const std::string& key, const std::string& vertex, const std::string& fragment,
                               const std::vector<std::string>& defines = {}) {
    auto it = programs.find(key);
    if (it == programs.end()) it = programs.emplace(key, ShaderProgram(vertex, fragment, defines)).first;
    return it->second;
  }

  void uploadGlyphMap(const GlyphMapSettings& g);
  void updateBeta(const BetaKey& key);
  void setFunctionalUniforms(ShaderProgram& p, float low, float high, int classes) const;

  // The program for a mode and its compile-time variants (features off cost nothing).
  ShaderProgram& program(RenderMode mode, const RenderSettings& s, bool fusion) {
    std::string file = "projection.frag.glsl";
    std::vector<std::string> defines;
    if (mode == RenderMode::Mip && s.depthCue) defines.push_back("MVW_DEPTH_CUE 1");
    if (mode == RenderMode::Composite) {
      if (s.gradientOpacityHigh > 0.0) defines.push_back("MVW_TF2D 1");
      if (fusion) defines.push_back("MVW_FUSION 1");
    }
    if ((mode == RenderMode::Composite || mode == RenderMode::Isosurface) && s.glyphs) {
      defines.push_back("MVW_GLYPHS 1");
      if (!s.glyphSizeControl) defines.push_back("MVW_GLYPH_SIMPLE 1");
      if (s.glyphConvexity == 1) defines.push_back("MVW_GLYPH_CONCAVE 1");
      if (s.glyphConvexity == 2) defines.push_back("MVW_GLYPH_BOTH 1");
      if (s.glyphMap.placement == GlyphPlacement::Paper) defines.push_back("MVW_GLYPH_PAPER 1");
    }
    switch (mode) {
      case RenderMode::Composite: file = "composite.frag.glsl"; break;
      case RenderMode::Isosurface: file = "isosurface.frag.glsl"; break;
      case RenderMode::Mip: defines.push_back("MVW_MIP 1"); break;
      case RenderMode::MinIp: defines = {"MVW_MINIP 1"}; break;
      case RenderMode::Average: defines = {"MVW_AVERAGE 1"}; break;
      case RenderMode::Mpr: file = "mpr.frag.glsl"; break;
      case RenderMode::ShellMip:
      case RenderMode::ShellSum:
      case RenderMode::ShellLit: break;  // drawn by detail::ShellRenderer
    }
    std::string key = toString(mode);
    for (const auto& d : defines) key += "+" + d;
    return cachedProgram(key, "fullscreen.vert.glsl", file, defines);
  }
};

void VolumeRenderer::Impl::uploadGlyphMap(const GlyphMapSettings& g) {
  if (glyphCells.id() && g.size == glyphMapSettings.size && g.count == glyphMapSettings.count &&
      g.diameter == glyphMapSettings.diameter && g.seed == glyphMapSettings.seed &&
      g.placement == glyphMapSettings.placement)
    return;
  const GlyphMap map = makeGlyphMap(g, /*texels=*/false);
  const int n = map.size / map.cellSize;
  glyphCells = detail::makeTexture();
  glBindTexture(GL_TEXTURE_3D, glyphCells.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, n, n, n, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, map.cells.data());
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_3D, wrap, GL_REPEAT);  // the map is periodic
  setSampling(glyphCells.id(), GL_TEXTURE_3D, false);
  std::vector<glm::vec4> centres(255, glm::vec4(0.0f));  // std140: one vec4 per centre
  for (std::size_t i = 0; i < map.centres.size(); ++i) centres[i] = glm::vec4(glm::vec3(map.centres[i]), 0.0f);
  glyphCentres = detail::makeBuffer();
  glBindBuffer(GL_UNIFORM_BUFFER, glyphCentres.id());
  glBufferData(GL_UNIFORM_BUFFER, GLsizeiptr(centres.size() * sizeof(glm::vec4)), centres.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  checkGl("uploading the glyph map");
  glyphMapSettings = g;
  glyphRadius = map.radius;
}

void VolumeRenderer::Impl::setFunctionalUniforms(ShaderProgram& p, float low, float high, int classes) const {
  const glm::mat4 functionalFromWorld(functionalTextureFromAnatomicalWorld);
  glUniformMatrix4fv(p.uniform("uFunctionalFromWorld"), 1, GL_FALSE, glm::value_ptr(functionalFromWorld));
  glUniform2f(p.uniform("uFunctionalRange"), low, high);
  glUniform1i(p.uniform("uFunctionalClasses"), std::max(0, classes));
}

// The functional attribute through the view's mapping, resampled onto the anatomical grid
// and written into the gradient texture's alpha one slice at a time (colour mask: alpha
// only), so the ray loop reads beta with the gradient instead of sampling a second volume.
void VolumeRenderer::Impl::updateBeta(const BetaKey& key) {
  if (betaKey == key) return;
  ShaderProgram& p = cachedProgram("beta", "fullscreen.vert.glsl", "beta.frag.glsl");
  p.use();
  setFunctionalUniforms(p, key.low, key.high, key.classes);
  const glm::mat4 worldFromIndexF(worldFromIndex);
  glUniformMatrix4fv(p.uniform("uWorldFromIndex"), 1, GL_FALSE, glm::value_ptr(worldFromIndexF));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, functional.id());
  glUniform1i(p.uniform("uFunctional"), 0);
  detail::Framebuffer fbo = detail::makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  const GLenum buffer = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &buffer);
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, gradient.id(), 0, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    throw Error("the GL cannot render into the gradient volume (RGBA16F) for glyph shading");
  }
  glViewport(0, 0, dims.x, dims.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  glBindVertexArray(vao.id());
  for (int k = 0; k < dims.z; ++k) {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, gradient.id(), 0, k);
    glUniform1f(p.uniform("uSlice"), float(k));
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("resampling the functional volume for glyph shading");
  betaKey = key;
}

VolumeRenderer::VolumeRenderer(GlContext& context, const Volume& volume) : impl_(std::make_unique<Impl>(context)) {
  Impl& m = *impl_;
  context.makeCurrent();
  m.dims = volume.dimensions();
  m.worldFromIndex = volume.worldFromIndex();
  m.spacing = volume.spacing();
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  if (m.dims.x > max3d || m.dims.y > max3d || m.dims.z > max3d)
    throw Error("volume " + std::to_string(m.dims.x) + " x " + std::to_string(m.dims.y) + " x " +
                std::to_string(m.dims.z) + " exceeds the GL's largest 3D texture (" + std::to_string(max3d) + ")");
  m.values = valuesOf(volume);
  const std::vector<float>& values = m.values;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  m.range = {*lo, *hi};

  // Sampling of the intensity (linear or nearest) is set per frame.
  m.intensity = upload3D(m.dims, GL_R32F, GL_RED, values.data(), true, "uploading the volume");
  const std::vector<float> grad = gradientOf(values, m.dims, m.spacing, volume.direction());
  m.gradient = upload3D(m.dims, GL_RGBA16F, GL_RGBA, grad.data(), true, "uploading the gradient volume");

  // Min/max per 8^3 block, widened by one voxel: trilinear samples near a block's face read
  // the neighbour's voxels too.
  m.blockCount = (m.dims + kBlock - 1) / kBlock;
  m.blockMinMax.assign(static_cast<std::size_t>(m.blockCount.x) * m.blockCount.y * m.blockCount.z,
                       glm::vec2(3.4e38f, -3.4e38f));
  for (int k = 0; k < m.dims.z; ++k)
    for (int j = 0; j < m.dims.y; ++j)
      for (int i = 0; i < m.dims.x; ++i) {
        const float v = values[(static_cast<std::size_t>(k) * m.dims.y + j) * m.dims.x + i];
        for (int bk = std::max(0, (k - 1) / kBlock); bk <= std::min(m.blockCount.z - 1, (k + 1) / kBlock); ++bk)
          for (int bj = std::max(0, (j - 1) / kBlock); bj <= std::min(m.blockCount.y - 1, (j + 1) / kBlock); ++bj)
            for (int bi = std::max(0, (i - 1) / kBlock); bi <= std::min(m.blockCount.x - 1, (i + 1) / kBlock); ++bi) {
              glm::vec2& b = m.blockMinMax[(static_cast<std::size_t>(bk) * m.blockCount.y + bj) * m.blockCount.x + bi];
              b.x = std::min(b.x, v);
              b.y = std::max(b.y, v);
            }
      }
  m.blocks = detail::makeTexture();
  m.blockRange = detail::makeTexture();
  glBindTexture(GL_TEXTURE_3D, m.blockRange.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RG32F, m.blockCount.x, m.blockCount.y, m.blockCount.z, 0, GL_RG, GL_FLOAT,
               m.blockMinMax.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  checkGl("uploading the block grid");
  m.transfer = detail::makeTexture();
  m.vao = detail::makeVertexArray();
}

VolumeRenderer::~VolumeRenderer() = default;

std::pair<double, double> VolumeRenderer::valueRange() const { return impl_->range; }

glm::dvec3 VolumeRenderer::centre() const {
  const Impl& m = *impl_;
  return 0.5 * (glm::dvec3(m.worldFromIndex * glm::dvec4(-0.5, -0.5, -0.5, 1.0)) +
                glm::dvec3(m.worldFromIndex * glm::dvec4(glm::dvec3(m.dims) - 0.5, 1.0)));
}

double VolumeRenderer::radius() const { return 0.5 * glm::length(glm::dvec3(impl_->dims) * impl_->spacing); }

bool VolumeRenderer::hasFunctional() const { return impl_->functional.id() != 0; }

std::pair<double, double> VolumeRenderer::functionalRange() const { return impl_->functionalRange; }

void VolumeRenderer::setFunctional(const Volume& functional, const glm::dmat4& anatomicalFromFunctional) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  const glm::ivec3 d = functional.dimensions();
  const std::vector<float> values = valuesOf(functional);
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  m.functionalRange = {*lo, *hi > *lo ? *hi : *lo + 1.0f};
  // Label maps keep their classes: nearest; other attributes are interpolated.
  m.functional = upload3D(d, GL_R32F, GL_RED, values.data(), !isInteger(functional.scalarType()),
                          "uploading the functional volume");
  ++m.functionalGeneration;
  glm::dmat4 textureFromIndex(1.0);
  for (int a = 0; a < 3; ++a) {
    textureFromIndex[a][a] = 1.0 / d[a];
    textureFromIndex[3][a] = 0.5 / d[a];
  }
  m.functionalTextureFromAnatomicalWorld =
      textureFromIndex * glm::inverse(functional.worldFromIndex()) * glm::inverse(anatomicalFromFunctional);
  const std::vector<glm::vec4> lut =
      sampleTransferFunction(transferPreset("pet-hot-metal"), 0.0, 1.0, 256, 0.0, 1.0);
  std::vector<glm::vec4> opaque = lut;
  for (auto& c : opaque) c.a = 1.0f;
  m.colormap = detail::makeTexture();
  glBindTexture(GL_TEXTURE_1D, m.colormap.id());
  glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA32F, 256, 0, GL_RGBA, GL_FLOAT, opaque.data());
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
}

Frame VolumeRenderer::render(const RenderSettings& s) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  if (s.size.x <= 0 || s.size.y <= 0 || s.size.x > 8192 || s.size.y > 8192)
    throw Error("image size must be 1..8192 pixels a side");
  const auto start = std::chrono::steady_clock::now();

  // Camera around the volume's bounding sphere.
  const glm::dvec3 centre = this->centre();
  const double radius = this->radius();
  Frame frame;
  CameraSettings cameraSettings = s.camera;
  if (s.mode == RenderMode::Mpr) cameraSettings.perspective = false;
  frame.camera = makeCamera(cameraSettings, centre, radius, s.size);

  if (s.mode == RenderMode::ShellMip || s.mode == RenderMode::ShellSum || s.mode == RenderMode::ShellLit) {
    // The paper's transform is affine in z, so the shells are drawn orthographically.
    CameraSettings ortho = s.camera;
    ortho.perspective = false;
    frame.camera = makeCamera(ortho, centre, radius, s.size);
    if (!m.shells) m.shells = std::make_unique<detail::ShellRenderer>(m.values, m.dims, m.worldFromIndex);
    detail::ShellDraw d;
    d.mode = s.mode == RenderMode::ShellMip ? detail::ShellMode::Maximum
             : s.mode == RenderMode::ShellSum ? detail::ShellMode::Summation : detail::ShellMode::Lit;
    d.size = s.size;
    d.camera = frame.camera;
    d.centre = centre;
    d.radius = radius;
    const double w = s.window > 0 ? s.window : m.range.second - m.range.first;
    const double l = s.window > 0 ? s.level : 0.5 * (m.range.first + m.range.second);
    d.windowLow = l - 0.5 * w;
    d.windowWidth = w;
    d.count = s.shellCount;
    d.enabled = s.shellEnabled;
    if (s.depthCue) {
      d.cueBrightness = s.cueBrightness;
      d.cueAmount = s.cueAmount;
      d.cueContrast = s.cueContrast;
    }
    d.light = s.light;
    frame.image = m.shells->draw(d);
    frame.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return frame;
  }

  // Transfer function table over the value range (and the gradient magnitude for a 2D
  // function), its opacity corrected for this frame's step here rather than per sample.
  const int lutSize = 1024;
  const double lo = m.range.first, hi = m.range.second > m.range.first ? m.range.second : m.range.first + 1.0;
  const double minSpacing = std::min({m.spacing.x, m.spacing.y, m.spacing.z});
  const double step = s.stepMm > 0 ? s.stepMm : 0.5 * minSpacing;
  const std::vector<glm::vec4> lut = sampleTransferFunction(s.transfer, lo, hi, lutSize, lo, hi);
  const bool transfer2d = s.gradientOpacityHigh > 0.0;
  const int rows = transfer2d ? 64 : 1;
  const double gradientMax = transfer2d ? 2.0 * s.gradientOpacityHigh : 1.0;
  std::vector<glm::vec4> table(static_cast<std::size_t>(lutSize) * rows);
  for (int r = 0; r < rows; ++r) {
    double scale = 1.0;
    if (transfer2d) {
      const double g = gradientMax * r / (rows - 1);
      const double x = std::clamp((g - s.gradientOpacityLow) / std::max(1e-9, s.gradientOpacityHigh - s.gradientOpacityLow), 0.0, 1.0);
      scale = x * x * (3.0 - 2.0 * x);
    }
    for (int i = 0; i < lutSize; ++i) {
      glm::vec4 c = lut[i];
      const double a = std::min(0.999999, c.a * scale);
      c.a = static_cast<float>(1.0 - std::pow(1.0 - a, step / minSpacing));
      table[static_cast<std::size_t>(r) * lutSize + i] = c;
    }
  }
  glBindTexture(GL_TEXTURE_2D, m.transfer.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, lutSize, rows, 0, GL_RGBA, GL_FLOAT, table.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  std::vector<std::uint8_t> visible(m.blockMinMax.size(), 1);
  if (s.mode == RenderMode::Composite) {
    for (std::size_t b = 0; b < visible.size(); ++b) {
      const auto e0 = static_cast<int>(std::floor((m.blockMinMax[b].x - lo) / (hi - lo) * (lutSize - 1)));
      const auto e1 = static_cast<int>(std::ceil((m.blockMinMax[b].y - lo) / (hi - lo) * (lutSize - 1)));
      bool any = false;
      for (int e = std::max(0, e0); e <= std::min(lutSize - 1, e1) && !any; ++e) any = lut[e].a > 0.0f;
      visible[b] = any;
    }
  }
  glBindTexture(GL_TEXTURE_3D, m.blocks.id());
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R8UI, m.blockCount.x, m.blockCount.y, m.blockCount.z, 0, GL_RED_INTEGER,
               GL_UNSIGNED_BYTE, visible.data());
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  setSampling(m.intensity.id(), GL_TEXTURE_3D, s.linear);

  // Glyph shading: the map's cells and centres, and the attribute in the gradient's alpha.
  if (s.glyphs && m.functional.id() == 0)
    throw Error("glyph rendering needs a functional volume (the study has none)");
  if (s.glyphs && !(s.glyphDiameterMm > 0)) throw Error("glyph diameter must be positive");
  const bool userWindow = s.functionalHigh > s.functionalLow;
  const float functionalLow = float(userWindow ? s.functionalLow : m.functionalRange.first);
  const float functionalHigh = float(userWindow ? s.functionalHigh : m.functionalRange.second);
  if (s.glyphs) {
    m.uploadGlyphMap(s.glyphMap);
    m.updateBeta({m.functionalGeneration, functionalLow, functionalHigh, s.functionalClasses});
  }

  // Targets: RGBA8 colour and R32F ray depth.
  detail::Texture colorTex = detail::makeTexture(), depthTex = detail::makeTexture();
  glBindTexture(GL_TEXTURE_2D, colorTex.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, s.size.x, s.size.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glBindTexture(GL_TEXTURE_2D, depthTex.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, s.size.x, s.size.y, 0, GL_RED, GL_FLOAT, nullptr);
  detail::Framebuffer fbo = detail::makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTex.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, depthTex.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, buffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("render target of " + std::to_string(s.size.x) + " x " + std::to_string(s.size.y) + " is not supported");
  checkGl("creating the render target");

  const bool overlay = m.functional.id() != 0 && (s.mode == RenderMode::Mpr ? s.overlay : s.fusion);
  ShaderProgram& p = m.program(s.mode, s, overlay);
  p.use();
  // textureFromWorld = textureFromIndex * indexFromWorld; texel centres at (i + 0.5) / n.
  glm::dmat4 textureFromIndex(1.0);
  for (int a = 0; a < 3; ++a) {
    textureFromIndex[a][a] = 1.0 / m.dims[a];
    textureFromIndex[3][a] = 0.5 / m.dims[a];
  }
  const glm::mat4 textureFromWorld(textureFromIndex * glm::inverse(m.worldFromIndex));
  glUniformMatrix4fv(p.uniform("uVolume.textureFromWorld"), 1, GL_FALSE, glm::value_ptr(textureFromWorld));
  glUniform3f(p.uniform("uVolume.dimensions"), float(m.dims.x), float(m.dims.y), float(m.dims.z));
  glUniform1f(p.uniform("uVolume.referenceStep"), float(minSpacing));
  glUniform2f(p.uniform("uVolume.valueRange"), float(lo), float(hi));
  glUniform1f(p.uniform("uBlockVoxels"), float(kBlock));
  const glm::mat4 worldFromClip(frame.camera.worldFromClip);
  glUniformMatrix4fv(p.uniform("uWorldFromClip"), 1, GL_FALSE, glm::value_ptr(worldFromClip));
  glUniform2f(p.uniform("uViewport"), float(s.size.x), float(s.size.y));
  glUniform1f(p.uniform("uStep"), float(step));
  glUniform1i(p.uniform("uMaxSteps"), static_cast<int>(std::ceil(2.0 * radius / step)) + 2);
  glUniform1i(p.uniform("uJitter"), s.jitter ? 1 : 0);
  glUniform1ui(p.uniform("uSeed"), s.seed);
  const glm::dvec3 cmin = glm::clamp(s.cropMin, 0.0, 1.0), cmax = glm::clamp(s.cropMax, 0.0, 1.0);
  glUniform3f(p.uniform("uBoxMin"), float(cmin.x), float(cmin.y), float(cmin.z));
  glUniform3f(p.uniform("uBoxMax"), float(cmax.x), float(cmax.y), float(cmax.z));
  glUniform3f(p.uniform("uBackground"), s.background.r, s.background.g, s.background.b);
  glUniform4f(p.uniform("uLight"), s.light.x, s.light.y, s.light.z, s.light.w);
  const glm::vec3 lightDir(glm::normalize(-frame.camera.forward + s.lightOffset.x * frame.camera.right +
                                          s.lightOffset.y * frame.camera.up));
  glUniform3f(p.uniform("uLightDir"), lightDir.x, lightDir.y, lightDir.z);
  glUniform1i(p.uniform("uHeadlight"), s.lightOffset == glm::dvec2(0.0) ? 1 : 0);
  glUniform2f(p.uniform("uTransferRange"), float(1.0 / (hi - lo)), float(-lo / (hi - lo)));
  glUniform1i(p.uniform("uShading"), s.shading ? 1 : 0);
  glUniform1f(p.uniform("uGradientScale"), float(1.0 / gradientMax));
  const double window = s.window > 0 ? s.window : hi - lo;
  const double level = s.window > 0 ? s.level : 0.5 * (hi + lo);
  glUniform2f(p.uniform("uWindowLevel"), float(window), float(level));
  glUniform1f(p.uniform("uIsoValue"), float(s.isoValue));
  glUniform3f(p.uniform("uCue"), float(s.cueBrightness), float(s.cueAmount), float(s.cueContrast));
  glUniform4f(p.uniform("uBoundingSphere"), float(centre.x), float(centre.y), float(centre.z), float(radius));
  glUniform4f(p.uniform("uIsoColor"), s.isoColor.r, s.isoColor.g, s.isoColor.b, s.isoColor.a);
  const glm::vec3 planeCentre(centre + frame.camera.forward * s.planeOffsetMm);
  glUniform3f(p.uniform("uPlaneCentre"), planeCentre.x, planeCentre.y, planeCentre.z);
  glUniform1f(p.uniform("uSlab"), float(std::max(0.0, s.slabMm)));
  if (s.glyphs) {
    const GLuint block = glGetUniformBlockIndex(p.id(), "GlyphCentres");
    if (block != GL_INVALID_INDEX) {
      glUniformBlockBinding(p.id(), block, 0);
      glBindBufferBase(GL_UNIFORM_BUFFER, 0, m.glyphCentres.id());
    }
    const double voxelsPerMm = s.glyphMap.diameter / s.glyphDiameterMm;
    const glm::mat3 glyphFromWorld(voxelsPerMm * glyphMapRotation(s.glyphMap.placement));
    glUniformMatrix3fv(p.uniform("uGlyphFromWorld"), 1, GL_FALSE, glm::value_ptr(glyphFromWorld));
    glUniform1f(p.uniform("uGlyphMapSize"), float(s.glyphMap.size));
    glUniform1f(p.uniform("uGlyphInvMapSize"), float(1.0 / s.glyphMap.size));
    glUniform1f(p.uniform("uGlyphRadius"), float(m.glyphRadius));
    glUniform1f(p.uniform("uGlyphMinSize"), float(std::clamp(s.glyphMinSize, 0.0, 1.0)));
  }
  m.setFunctionalUniforms(p, functionalLow, functionalHigh, s.functionalClasses);
  glUniform1i(p.uniform("uHasFunctional"), overlay ? 1 : 0);
  glUniform1f(p.uniform("uOverlayOpacity"), s.overlayOpacity);
  glUniform1f(p.uniform("uOverlayThreshold"), s.overlayThreshold);
  const struct { const char* name; GLenum target; GLuint id; } units[] = {
      {"uIntensity", GL_TEXTURE_3D, m.intensity.id()}, {"uGradient", GL_TEXTURE_3D, m.gradient.id()},
      {"uBlocks", GL_TEXTURE_3D, m.blocks.id()},       {"uTransfer", GL_TEXTURE_2D, m.transfer.id()},
      {"uBlockRange", GL_TEXTURE_3D, m.blockRange.id()}, {"uFunctional", GL_TEXTURE_3D, m.functional.id()},
      {"uColormap", GL_TEXTURE_1D, m.colormap.id()},   {"uGlyphCells", GL_TEXTURE_3D, m.glyphCells.id()}};
  for (int u = 0; u < 8; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(units[u].target, units[u].id);
    glUniform1i(p.uniform(units[u].name), u);
  }
  glActiveTexture(GL_TEXTURE0);

  glViewport(0, 0, s.size.x, s.size.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(m.vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);

  Image& img = frame.image;
  img = Image(s.size.x, s.size.y);
  img.depth.resize(static_cast<std::size_t>(s.size.x) * s.size.y);
  std::vector<std::uint8_t> rgba(img.rgba.size());
  std::vector<float> depth(img.depth.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, s.size.x, s.size.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glReadBuffer(GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, s.size.x, s.size.y, GL_RED, GL_FLOAT, depth.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("rendering");
  // GL rows start at the bottom; images at the top.
  const std::size_t row = static_cast<std::size_t>(s.size.x) * 4;
  for (int y = 0; y < s.size.y; ++y) {
    std::copy_n(rgba.data() + (s.size.y - 1 - y) * row, row, img.rgba.data() + y * row);
    std::copy_n(depth.data() + static_cast<std::size_t>(s.size.y - 1 - y) * s.size.x, s.size.x,
                img.depth.data() + static_cast<std::size_t>(y) * s.size.x);
  }
  frame.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

}  // namespace mvw::render
