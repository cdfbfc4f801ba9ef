// io MovieWriter, which `mvw render` writes orbits with: every frame, odd sizes padded to even,
// and atomic output (the movie appears whole at finish(), an abandoned one leaves nothing).
#include <cstdint>
#include <filesystem>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/core/Image.h"
#include "mvw/io/MovieWriter.h"

namespace mvw {
namespace {

namespace fs = std::filesystem;

Image solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  return img;
}

TEST(MovieWriter, WritesEveryFrameAtAnEvenSizeAndAppearsWhole) {
  const fs::path dir = test::scratchDir();
  for (const char* name : {"spin.mp4", "spin.avi"}) {
    const fs::path path = dir / name;
    {
      io::MovieWriter movie(path, 161, 121, 10.0);  // odd: padded to 162 x 122
      for (int k = 0; k < 13; ++k)
        movie.add(solid(161, 121, std::uint8_t(20 * k), 128, std::uint8_t(255 - 20 * k)));
      EXPECT_FALSE(fs::exists(path)) << "visible before finish()";
      movie.finish();
      EXPECT_EQ(movie.frames(), 13);
      EXPECT_EQ(movie.width(), 162);
      EXPECT_EQ(movie.height(), 122);
    }
    const io::MovieInfo info = io::readMovieInfo(path);
    EXPECT_EQ(info.frames, 13) << name;
    EXPECT_EQ(info.width, 162) << name;
    EXPECT_EQ(info.height, 122) << name;
  }
  {
    io::MovieWriter abandoned(dir / "abandoned.mp4", 32, 32, 10.0);
    abandoned.add(solid(32, 32, 1, 2, 3));
    EXPECT_THROW(abandoned.add(solid(16, 32, 1, 2, 3)), Error);  // a frame of another size
  }
  // Nothing left behind: not the movie, not its temporary.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_TRUE(e.path().filename() == "spin.mp4" || e.path().filename() == "spin.avi") << e.path();
  EXPECT_THROW(io::MovieWriter(dir / "spin.gif", 32, 32, 10.0), Error);
  EXPECT_THROW(io::readMovieInfo(dir / "missing.mp4"), Error);
}

}  // namespace
}  // namespace mvw
