// Image metrics (validate ImageMetrics), by which `mvw validate` passes or fails a rendering:
// PSNR, the differing-pixel count, mean delta and SSIM against hand-computed values.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "mvw/core/Image.h"
#include "mvw/validate/ImageMetrics.h"

namespace mvw::validate {
namespace {

TEST(ImageMetrics, PsnrOfKnownErrors) {
  EXPECT_EQ(psnrFromMse(0.0), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(psnrFromMse(255.0 * 255.0), 0.0);
  EXPECT_NEAR(psnrFromMse(1.0), 48.1308, 1e-4);
  Image a(4, 4), b(4, 4);
  EXPECT_EQ(psnr(a, b), std::numeric_limits<double>::infinity());
  b.pixel(1, 1)[0] = 48;   // one channel of one pixel off by 48: mse = 48^2 / 48 values
  b.pixel(1, 1)[3] = 200;  // alpha does not count
  EXPECT_NEAR(psnr(a, b), 10 * std::log10(255.0 * 255.0 / 48.0), 1e-9);
}

TEST(ImageMetrics, CompareImagesCountsTheDifferingPixels) {
  cv::Mat a(10, 10, CV_8UC3, cv::Scalar(100, 100, 100));
  cv::Mat b = a.clone();
  b.at<cv::Vec3b>(2, 3)[1] = 130;  // +30 on one channel
  b.at<cv::Vec3b>(5, 5)[2] = 110;  // +10, under the threshold
  const Metrics m = compareImages(b, a, 24.0);
  EXPECT_EQ(m.maxDelta, 30.0);
  EXPECT_DOUBLE_EQ(m.overFraction, 1.0 / 100.0);
  EXPECT_DOUBLE_EQ(m.meanDelta, 40.0 / 300.0);
  EXPECT_NEAR(m.psnr, 10 * std::log10(255.0 * 255.0 / ((900.0 + 100.0) / 300.0)), 1e-9);
  EXPECT_LT(m.ssim, 1.0);
  EXPECT_EQ(m.heat.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 0));  // identical pixels stay black
  EXPECT_NE(m.heat.at<cv::Vec3b>(2, 3), cv::Vec3b(0, 0, 0));
  EXPECT_DOUBLE_EQ(ssimGrey(a, a), 1.0);
}

}  // namespace
}  // namespace mvw::validate
