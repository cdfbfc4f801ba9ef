// What the viewer's window loop writes of its frames (mvw/viewer/ViewerFrames.h): the frame
// log's header and lines, and a pane's rectangle of the window's image, clipped to the window.
#include "mvw/viewer/ViewerFrames.h"

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "TestUtil.h"
#include "mvw/core/Error.h"

namespace mvw::viewer {
namespace {

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(FrameLog, HeaderThenALinePerFrame) {
  const std::filesystem::path file = test::scratchDir() / "frames.csv";
  {
    FrameLog log(file);
    log.start();
    log.frame(0, 12.5, {640, 480}, true, 2);
    log.frame(1, 0.0, {0, 0}, false, 0);
  }
  std::istringstream lines(read(file));
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header, "frame,ms,render3d_ms,render3d_width,render3d_height,interactive,drag_divisor");
  // The ms since the previous swap is a time: only its place is checked.
  EXPECT_EQ(first.substr(0, 2), "0,");
  EXPECT_EQ(first.substr(first.find(',', 2)), ",12.5,640,480,1,2");
  EXPECT_EQ(second.substr(0, 2), "1,");
  EXPECT_EQ(second.substr(second.find(',', 2)), ",0,0,0,0,0");
}

TEST(FrameLog, NoPathNoLog) {
  FrameLog log{std::filesystem::path()};
  log.frame(0, 1.0, {1, 1}, false, 0);  // nothing to write to: nothing happens
}

TEST(FrameLog, AnUnwritablePathIsBadInput) {
  EXPECT_THROW(FrameLog(test::scratchDir() / "no-such-folder" / "frames.csv"), InputError);
}

TEST(PaneImage, CopiesThePanesRectangleClippedToTheWindow) {
  Image window(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) window.pixel(x, y)[0] = static_cast<std::uint8_t>(10 * y + x);
  const Image pane = paneImage(window, {1, 1}, {2, 2});
  ASSERT_EQ(pane.width, 2);
  ASSERT_EQ(pane.height, 2);
  EXPECT_EQ(pane.pixel(0, 0)[0], 11);
  EXPECT_EQ(pane.pixel(1, 1)[0], 22);
  const Image clipped = paneImage(window, {3, 2}, {5, 5});
  EXPECT_EQ(clipped.width, 1);
  EXPECT_EQ(clipped.height, 1);
  EXPECT_EQ(clipped.pixel(0, 0)[0], 23);
  EXPECT_EQ(paneImage(window, {-3, -3}, {2, 2}).width, 0);
}

}  // namespace
}  // namespace mvw::viewer
