// The registration QA picture (issue 3), by which a reader judges a registration: overlay and
// checkerboard rows before and after, not blank, and differing exactly where the transforms do.
#include <cmath>
#include <cstdint>
#include <cstring>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "RegistrationTestUtil.h"
#include "mvw/resampling/RegistrationQa.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {
namespace {

// Mean absolute RGB difference between two equal-sized bands of rows of an image, right of
// the 22-pixel margin that holds the row names.
double bandDifference(const Image& image, int rowA, int rowB, int height) {
  double sum = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 22; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        sum += std::abs(image.pixel(x, rowA + y)[c] - image.pixel(x, rowB + y)[c]);
  return sum / (3.0 * height * (image.width - 22));
}

TEST(RegistrationQa, ShowsTheOverlayBeforeAndAfter) {
  const Volume fixed = blobs({0, 0, 0});
  const Volume moving = blobs({6, 0, 0});  // content 6 mm further +x
  const Transform identity;
  const Transform aligned(glm::translate(glm::dmat4(1.0), glm::dvec3(-6, 0, 0)));
  RegistrationQaOptions options;
  options.panelPixels = 120;
  const Image image = registrationQaImage(fixed, moving, identity, aligned, options);
  // Four rows of panels (overlay and checkerboard, before and after) under a title row.
  ASSERT_GT(image.width, 3 * 100);
  ASSERT_EQ(image.rgba.size(), static_cast<std::size_t>(image.width) * image.height * 4);
  const int title = 22, cell = (image.height - title) / 4;
  ASSERT_EQ(title + 4 * cell, image.height);
  ASSERT_GE(cell, 100);

  // Not blank: grey levels spread, and the functional volume shows in colour.
  double sum = 0, sum2 = 0;
  int coloured = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      const double l = (p[0] + p[1] + p[2]) / 3.0;
      sum += l;
      sum2 += l * l;
      coloured += std::abs(p[0] - p[2]) > 60;
      ASSERT_EQ(p[3], 255);
    }
  const double n = double(image.width) * image.height;
  EXPECT_GT(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 20.0);
  EXPECT_GT(coloured, 2000);
  // Before and after differ where the transforms do, in the overlay and checkerboard rows.
  EXPECT_GT(bandDifference(image, title, title + cell, cell), 2.0);
  EXPECT_GT(bandDifference(image, title + 2 * cell, title + 3 * cell, cell), 2.0);
  // ... and are the same picture when the transforms are the same.
  const Image same = registrationQaImage(fixed, moving, aligned, aligned, options);
  EXPECT_EQ(bandDifference(same, title, title + cell, cell), 0.0);
  EXPECT_EQ(bandDifference(same, title + 2 * cell, title + 3 * cell, cell), 0.0);
  // The "after" rows of both pictures match: the after overlay does not depend on `before`.
  for (int y = title + cell; y < title + 2 * cell; ++y)
    for (int x = title; x < image.width; ++x)
      ASSERT_EQ(std::memcmp(same.pixel(x, y), image.pixel(x, y), 4), 0) << x << "," << y;
}

}  // namespace
}  // namespace mvw::resampling
