// Needs a GL context (OSMesa, headless): the types the viewer draws and reads its window with,
// so that it never calls GL itself.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "mvw/render/DisplayTexture.h"
#include "mvw/render/GlContext.h"
#include "mvw/render/WindowFramebuffer.h"

namespace mvw::render {
namespace {

// Intentional odd size: an RGBA row of 13 pixels is 52 bytes, catching alignment mistakes.
Image gradient(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(x * 19);
      p[1] = static_cast<std::uint8_t>(y * 23);
      p[2] = static_cast<std::uint8_t>(x + y);
      p[3] = 255;
    }
  return image;
}

TEST(DisplayTexture, HoldsTheImageRowForRow) {
  auto ctx = createHeadlessContext({8, 8});
  DisplayTexture texture;
  EXPECT_TRUE(texture.empty());
  const Image image = gradient(13, 7);
  texture.upload(image);
  ASSERT_FALSE(texture.empty());
  EXPECT_EQ(texture.size(), glm::ivec2(13, 7));
  std::vector<std::uint8_t> texels(image.rgba.size());
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture.handle()));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(texels, image.rgba);  // row 0 first: v = 0 is the image's top
}

TEST(DisplayTexture, MovesOwnershipAndDeletesOnce) {
  auto ctx = createHeadlessContext({8, 8});
  DisplayTexture a;
  a.upload(gradient(3, 2));
  const auto name = static_cast<GLuint>(a.handle());
  DisplayTexture b(std::move(a));
  EXPECT_TRUE(a.empty());  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
  EXPECT_EQ(b.handle(), name);
  DisplayTexture c;
  c = std::move(b);
  EXPECT_EQ(c.handle(), name);
  EXPECT_TRUE(glIsTexture(name));
  c = DisplayTexture();
  EXPECT_FALSE(glIsTexture(name));
}

TEST(WindowFramebuffer, ClearsTheWholeBufferAndReadsItTopRowFirst) {
  auto ctx = createHeadlessContext({11, 5});
  WindowFramebuffer framebuffer(*ctx);
  framebuffer.clear({0.2f, 0.4f, 0.6f, 1.0f});
  // The bottom two GL rows in another colour: they must come back as the last two rows.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 11, 2);
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const Image image = framebuffer.read();
  ASSERT_EQ(image.width, 11);
  ASSERT_EQ(image.height, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 11; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      const std::array<int, 4> want =
          y >= 3 ? std::array<int, 4>{255, 0, 0, 255} : std::array<int, 4>{51, 102, 153, 255};
      ASSERT_EQ((std::array<int, 4>{p[0], p[1], p[2], p[3]}), want) << x << ", " << y;
    }
}

}  // namespace
}  // namespace mvw::render
