#include "ShellRenderer.h"

#include "ReadPixels.h"

#include <algorithm>
#include <cmath>

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include "mvw/core/Error.h"

namespace mvw::render::detail {

struct ShellRenderer::Gpu {
  double emission = 0.0;
  VertexArray vao;
  Buffer vertices, indices;
  GLsizei indexCount = 0;
};

ShellRenderer::ShellRenderer(std::vector<float> values, glm::ivec3 dims,
                             const glm::dmat4& worldFromIndex)
    : values_(std::move(values)), dims_(dims), worldFromIndex_(worldFromIndex) {}

ShellRenderer::~ShellRenderer() = default;

std::size_t ShellRenderer::triangleCount() const {
  std::size_t n = 0;
  for (const auto& s : shells_) n += static_cast<std::size_t>(s->indexCount) / 3;
  return n;
}

void ShellRenderer::ensureShells(const ShellDraw& d) {
  if (cachedCount_ == d.count && cachedLow_ == d.windowLow && cachedWidth_ == d.windowWidth) return;
  shells_.clear();
  for (int i = 1; i <= d.count; ++i) {
    const double emission = static_cast<double>(i) / d.count;
    const ShellMesh mesh =
        extractShell(values_, dims_, worldFromIndex_, d.windowLow + emission * d.windowWidth);
    auto gpu = std::make_unique<Gpu>();
    gpu->emission = emission;
    gpu->vao = makeVertexArray();
    gpu->vertices = makeBuffer();
    gpu->indices = makeBuffer();
    glBindVertexArray(gpu->vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, gpu->vertices.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(float)),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->indices.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(unsigned)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glBindVertexArray(0);
    gpu->indexCount = static_cast<GLsizei>(mesh.indices.size());
    shells_.push_back(std::move(gpu));
  }
  cachedCount_ = d.count;
  cachedLow_ = d.windowLow;
  cachedWidth_ = d.windowWidth;
}

Image ShellRenderer::draw(const ShellDraw& d) {
  if (d.count < 1 || d.count > 256) throw Error("shell count must be 1..256");
  if (!d.enabled.empty() && static_cast<int>(d.enabled.size()) != d.count)
    throw Error("one enabled flag per shell is needed");
  ensureShells(d);
  auto found = programs_.find(d.mode);
  if (found == programs_.end()) {
    const char* define = d.mode == ShellMode::Maximum     ? "MVW_SHELL_MAX 1"
                         : d.mode == ShellMode::Summation ? "MVW_SHELL_SUM 1"
                                                          : "MVW_SHELL_LIT 1";
    found =
        programs_.emplace(d.mode, ShaderProgram("shells.vert.glsl", "shells.frag.glsl", {define}))
            .first;
  }
  ShaderProgram& program = found->second;

  Texture color = makeTexture(), depthOut = makeTexture();
  glBindTexture(GL_TEXTURE_2D, color.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, d.size.x, d.size.y, 0, GL_RGBA, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D, depthOut.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, d.size.x, d.size.y, 0, GL_RED, GL_FLOAT, nullptr);
  Texture depthBuffer = makeTexture();
  glBindTexture(GL_TEXTURE_2D, depthBuffer.id());
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, d.size.x, d.size.y, 0, GL_DEPTH_COMPONENT,
               GL_FLOAT, nullptr);
  Framebuffer fbo = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, depthOut.id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthBuffer.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, buffers);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("shell render target incomplete");

  glViewport(0, 0, d.size.x, d.size.y);
  const float clearColor[] = {0.0f, 0.0f, 0.0f, 1.0f};
  const float clearDepthOut[] = {-1.0f, 0.0f, 0.0f, 0.0f};
  glClearBufferfv(GL_COLOR, 0, clearColor);
  glClearBufferfv(GL_COLOR, 1, clearDepthOut);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  program.use();
  const glm::mat4 clipFromWorld(d.camera.clipFromWorld);
  glUniformMatrix4fv(program.uniform("uClipFromWorld"), 1, GL_FALSE, glm::value_ptr(clipFromWorld));
  glUniform3f(program.uniform("uForward"), float(d.camera.forward.x), float(d.camera.forward.y),
              float(d.camera.forward.z));
  glUniform4f(program.uniform("uBoundingSphere"), float(d.centre.x), float(d.centre.y),
              float(d.centre.z), float(d.radius));
  const DepthCue& cue = d.depthCue;
  glUniform3f(program.uniform("uCue"), float(cue.brightness), float(cue.amount),
              float(cue.contrast));
  glUniform1f(program.uniform("uKeyMax"),
              float(std::max(1e-6, cue.brightness + std::max(0.0, cue.amount) + cue.contrast)));
  glUniform1f(program.uniform("uWeight"), float(1.0 / d.count));
  glUniform4f(program.uniform("uLight"), d.light.x, d.light.y, d.light.z, d.light.w);
  if (d.mode == ShellMode::Summation) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);  // accumulate; each shell keeps only its nearest fragment
  }
  for (int i = 0; i < d.count; ++i) {
    if (!d.enabled.empty() && !d.enabled[i]) continue;
    const Gpu& shell = *shells_[static_cast<std::size_t>(i)];
    if (d.mode == ShellMode::Summation) glClear(GL_DEPTH_BUFFER_BIT);
    glUniform1f(program.uniform("uEmission"), float(shell.emission));
    glBindVertexArray(shell.vao.id());
    glDrawElements(GL_TRIANGLES, shell.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);

  glReadBuffer(GL_COLOR_ATTACHMENT0);
  const std::vector<float> rgba = readRowsTopDown<float>(d.size, GL_RGBA, GL_FLOAT, 4);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (glGetError() == GL_OUT_OF_MEMORY) throw Error("the GL ran out of memory drawing the shells");
  Image img(d.size.x, d.size.y);
  img.depth.assign(static_cast<std::size_t>(d.size.x) * d.size.y, -1.0f);
  for (int y = 0; y < d.size.y; ++y)
    for (int x = 0; x < d.size.x; ++x) {
      const float* src = &rgba[(static_cast<std::size_t>(y) * d.size.x + x) * 4];
      std::uint8_t* dst = img.pixel(x, y);
      for (int c = 0; c < 3; ++c)
        dst[c] = static_cast<std::uint8_t>(std::lround(std::clamp(src[c], 0.0f, 1.0f) * 255.0f));
      dst[3] = 255;
    }
  return img;
}

}  // namespace mvw::render::detail
