// The colour bar (render Annotations) drawn without GL: its labels must read on any background.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <gtest/gtest.h>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/render/Annotations.h"
#include "mvw/study/ViewPlan.h"

namespace mvw {

// The colour bar's labels (range ends and unit) on a white background, as an inverted-grey
// MIP has: every yellow text pixel has a dark pixel within 2 px (it sits on a dark box), so
// the text reads on any background.
TEST(ColourBar, LabelsReadOnAWhiteBackground) {
  for (const int width : {256, 700}) {
    Image image(width, 2 * width);
    std::fill(image.rgba.begin(), image.rgba.end(), std::uint8_t{255});
    render::drawColourBar(image, 0.0, 8.0, "SUVbw", study::colorTable(ColorMap::GreyInverted));
    auto px = [&](int x, int y) { return &image.rgba[(std::size_t(y) * image.width + x) * 4]; };
    int text = 0, bare = 0;
    for (int y = 2; y < image.height - 2; ++y)
      for (int x = 2; x < image.width - 2; ++x) {
        const std::uint8_t* p = px(x, y);
        if (!(p[0] > 200 && p[1] > 180 && p[2] < 150)) continue;  // the labels' yellow
        ++text;
        bool dark = false;
        for (int dy = -2; dy <= 2 && !dark; ++dy)
          for (int dx = -2; dx <= 2 && !dark; ++dx) {
            const std::uint8_t* q = px(x + dx, y + dy);
            dark = std::max({q[0], q[1], q[2]}) < 80;
          }
        bare += !dark;
      }
    EXPECT_GT(text, 20) << width;
    EXPECT_EQ(bare, 0) << width << ": yellow label pixels on white, with nothing dark around";
  }
}

}  // namespace mvw
