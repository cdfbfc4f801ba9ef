#include "mvw/validate/ImageMetrics.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "mvw/io/Png.h"

namespace mvw::validate {

namespace fs = std::filesystem;

double psnrFromMse(double mse) {
  return mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
}

double psnr(const Image& a, const Image& b) {
  double se = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(a.rgba[i]) - double(b.rgba[i]);
    se += d * d;
  }
  return psnrFromMse(se / (double(a.rgba.size()) * 3.0 / 4.0));
}

double ssimGrey(const cv::Mat& a, const cv::Mat& b) {
  auto grey = [](const cv::Mat& m) {
    cv::Mat g, d;
    if (m.channels() == 3)
      cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    else
      g = m;
    g.convertTo(d, CV_64F);
    return d;
  };
  const cv::Mat x = grey(a), y = grey(b);
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  auto blur = [](const cv::Mat& m) {
    cv::Mat o;
    cv::GaussianBlur(m, o, cv::Size(11, 11), 1.5, 1.5, cv::BORDER_REFLECT);
    return o;
  };
  const cv::Mat mx = blur(x), my = blur(y);
  const cv::Mat mxx = mx.mul(mx), myy = my.mul(my), mxy = mx.mul(my);
  const cv::Mat sxx = blur(x.mul(x)) - mxx, syy = blur(y.mul(y)) - myy, sxy = blur(x.mul(y)) - mxy;
  cv::Mat num = (2 * mxy + c1).mul(2 * sxy + c2);
  cv::Mat den = (mxx + myy + c1).mul(sxx + syy + c2);
  cv::Mat map;
  cv::divide(num, den, map);
  if (map.rows > 10 && map.cols > 10) map = map(cv::Rect(5, 5, map.cols - 10, map.rows - 10));
  return cv::mean(map)[0];
}

cv::Mat heatMap(const cv::Mat& perPixelDelta) {
  cv::Mat scaled, heat;
  perPixelDelta.convertTo(scaled, CV_8U, 8.0);
  cv::applyColorMap(scaled, heat, cv::COLORMAP_INFERNO);
  heat.setTo(cv::Scalar(0, 0, 0), perPixelDelta == 0);
  return heat;
}

Metrics compareImages(const cv::Mat& actual, const cv::Mat& reference, double deltaThreshold) {
  Metrics m;
  cv::Mat diff;
  cv::absdiff(actual, reference, diff);
  std::vector<cv::Mat> channels;
  cv::split(diff, channels);
  cv::Mat perPixel = channels[0].clone();
  for (std::size_t c = 1; c < channels.size(); ++c) perPixel = cv::max(perPixel, channels[c]);
  cv::minMaxLoc(perPixel, nullptr, &m.maxDelta);
  m.overFraction =
      cv::countNonZero(perPixel > deltaThreshold) / static_cast<double>(perPixel.total());
  cv::Mat d64;
  diff.convertTo(d64, CV_64F);
  const double values = static_cast<double>(diff.total()) * diff.channels();
  m.meanDelta = cv::sum(cv::sum(d64))[0] / values;
  const cv::Scalar sq = cv::sum(d64.mul(d64));
  m.psnr = psnrFromMse((sq[0] + sq[1] + sq[2] + sq[3]) / values);
  m.ssim = ssimGrey(actual, reference);
  m.heat = heatMap(perPixel);
  return m;
}

void writeMatPng(const cv::Mat& m, const fs::path& path) {
  cv::Mat rgba;
  if (m.channels() == 1)
    cv::cvtColor(m, rgba, cv::COLOR_GRAY2RGBA);
  else
    cv::cvtColor(m, rgba, cv::COLOR_BGR2RGBA);
  Image img(rgba.cols, rgba.rows);
  for (int r = 0; r < rgba.rows; ++r)
    std::memcpy(img.pixel(0, r), rgba.ptr(r), static_cast<std::size_t>(rgba.cols) * 4);
  io::writePng(img, path);
}

}  // namespace mvw::validate
