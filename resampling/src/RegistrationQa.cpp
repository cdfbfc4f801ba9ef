#include "mvw/resampling/RegistrationQa.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mvw/core/Check.h"
#include "mvw/resampling/Resample.h"

namespace mvw::resampling {

namespace {

constexpr int kTile = 16;   // checkerboard tile, pixels
constexpr int kLabel = 22;  // height of the title rows and width of the row labels, pixels

struct Plane {
  const char* name;
  glm::dvec3 u, v;  // world directions of the image's columns and rows (LPS)
};
// LPS: +x left, +y posterior, +z superior.
const std::array<Plane, 3> kPlanes = {{{"axial", {1, 0, 0}, {0, 1, 0}},
                                       {"coronal", {1, 0, 0}, {0, 0, -1}},
                                       {"sagittal", {0, 1, 0}, {0, 0, -1}}}};

// The world box of a volume's voxel centres.
void worldBox(const Volume& v, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(1e300);
  hi = glm::dvec3(-1e300);
  const glm::dvec3 d = glm::dvec3(v.dimensions() - 1);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p = v.worldFromIndexPoint({c & 1 ? d.x : 0, c & 2 ? d.y : 0, c & 4 ? d.z : 0});
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
}

// Values of a one-slice resample as a float image (rows x cols).
cv::Mat asMat(const Volume& slice) {
  const glm::ivec3 d = slice.dimensions();
  cv::Mat m(d.y, d.x, CV_32F);
  for (int j = 0; j < d.y; ++j)
    for (int i = 0; i < d.x; ++i) m.at<float>(j, i) = static_cast<float>(slice.value(i, j, 0));
  return m;
}

// The q-quantile of the values of some images, every 3rd pixel.
double quantile(const std::vector<cv::Mat>& images, double q) {
  std::vector<float> values;
  for (const cv::Mat& m : images)
    for (int j = 0; j < m.rows; ++j)
      for (int i = j % 3; i < m.cols; i += 3) values.push_back(m.at<float>(j, i));
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

cv::Mat toGrey(const cv::Mat& values, double lo, double hi) {
  cv::Mat grey;
  const double scale = hi > lo ? 255.0 / (hi - lo) : 0.0;
  values.convertTo(grey, CV_8U, scale, -lo * scale);
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

cv::Mat overlay(const cv::Mat& anatomy, const cv::Mat& functional, double lo, double hi,
                double alpha) {
  cv::Mat bgr = toGrey(anatomy, lo, hi);
  cv::Mat level;
  const double top = std::max(quantile({functional}, 0.995), 1e-12);
  functional.convertTo(level, CV_8U, 255.0 / top);
  cv::Mat colour;
  cv::applyColorMap(level, colour, cv::COLORMAP_HOT);
  for (int j = 0; j < bgr.rows; ++j)
    for (int i = 0; i < bgr.cols; ++i) {
      // Transparent below 10 % of the top value, then rising to `alpha`.
      const double a =
          alpha * std::clamp((level.at<std::uint8_t>(j, i) / 255.0 - 0.1) / 0.4, 0.0, 1.0);
      auto& p = bgr.at<cv::Vec3b>(j, i);
      const auto& c = colour.at<cv::Vec3b>(j, i);
      for (int k = 0; k < 3; ++k) p[k] = cv::saturate_cast<std::uint8_t>((1 - a) * p[k] + a * c[k]);
    }
  return bgr;
}

cv::Mat checkerboard(const cv::Mat& anatomy, const cv::Mat& functional, double lo, double hi) {
  cv::Mat a = toGrey(anatomy, lo, hi);
  const cv::Mat f = toGrey(functional, 0.0, std::max(quantile({functional}, 0.995), 1e-12));
  for (int j = 0; j < a.rows; ++j)
    for (int i = 0; i < a.cols; ++i)
      if ((i / kTile + j / kTile) % 2) a.at<cv::Vec3b>(j, i) = f.at<cv::Vec3b>(j, i);
  return a;
}

void label(cv::Mat& canvas, const std::string& text, cv::Point at) {
  cv::putText(canvas, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

}  // namespace

Image registrationQaImage(const Volume& fixed, const Volume& moving, const Transform& before,
                          const Transform& after, const RegistrationQaOptions& options) {
  MVW_CHECK(!fixed.empty() && !moving.empty());
  glm::dvec3 lo, hi;
  worldBox(fixed, lo, hi);
  const glm::dvec3 centre = fixed.worldFromIndexPoint(glm::dvec3(fixed.dimensions() - 1) * 0.5);
  const glm::dvec3 extent = hi - lo;
  // One pixel size for every panel, so a millimetre is as long in each view.
  const double pixel =
      std::max({extent.x, extent.y, extent.z, 1e-6}) / std::max(8, options.panelPixels);
  double fixedMin = fixed.value(0, 0, 0, 0);
  {
    const glm::ivec3 d = fixed.dimensions();
    for (int k = 0; k < d.z; k += 2)
      for (int j = 0; j < d.y; j += 2)
        for (int i = 0; i < d.x; i += 2) fixedMin = std::min(fixedMin, fixed.value(i, j, k, 0));
  }

  std::array<cv::Mat, 3> anatomy;
  std::array<std::array<cv::Mat, 3>, 2> functional;  // [before/after][plane]
  for (std::size_t p = 0; p < kPlanes.size(); ++p) {
    const Plane& plane = kPlanes[p];
    const double width = std::abs(glm::dot(extent, plane.u)),
                 height = std::abs(glm::dot(extent, plane.v));
    const glm::ivec3 dims(std::max(1, static_cast<int>(std::lround(width / pixel)) + 1),
                          std::max(1, static_cast<int>(std::lround(height / pixel)) + 1), 1);
    const glm::dvec3 normal = glm::cross(plane.u, plane.v);
    glm::dmat4 worldFromIndex(1.0);
    worldFromIndex[0] = glm::dvec4(plane.u * pixel, 0.0);
    worldFromIndex[1] = glm::dvec4(plane.v * pixel, 0.0);
    worldFromIndex[2] = glm::dvec4(normal * pixel, 0.0);
    worldFromIndex[3] = glm::dvec4(
        centre - plane.u * (pixel * (dims.x - 1) * 0.5) - plane.v * (pixel * (dims.y - 1) * 0.5),
        1.0);
    const Grid grid{dims, worldFromIndex};
    ResampleOptions linear;
    linear.interpolation = Interpolation::Linear;
    linear.allComponents = false;
    ResampleOptions anatomyOptions = linear;
    anatomyOptions.background = fixedMin;
    anatomy[p] = asMat(resample(fixed, grid, Transform(), anatomyOptions));
    functional[0][p] = asMat(resample(moving, grid, before, linear));
    functional[1][p] = asMat(resample(moving, grid, after, linear));
  }
  const std::vector<cv::Mat> all(anatomy.begin(), anatomy.end());
  const double greyLo = quantile(all, 0.01), greyHi = quantile(all, 0.995);

  // Cells as large as the largest panel; panels centred in them on black.
  int cellW = 0, cellH = 0;
  for (const cv::Mat& m : anatomy) cellW = std::max(cellW, m.cols), cellH = std::max(cellH, m.rows);
  const int rows = 4, cols = 3;
  cv::Mat canvas(kLabel + rows * cellH, kLabel + cols * cellW, CV_8UC3, cv::Scalar(0, 0, 0));
  const std::array<const char*, 4> rowNames = {"before: overlay", "after: overlay",
                                               "before: checkerboard", "after: checkerboard"};
  for (int r = 0; r < rows; ++r) {
    const int stage = r % 2;  // 0 before, 1 after
    for (int c = 0; c < cols; ++c) {
      const auto p = static_cast<std::size_t>(c);
      const cv::Mat panel =
          r < 2 ? overlay(anatomy[p], functional[static_cast<std::size_t>(stage)][p], greyLo,
                          greyHi, options.overlayAlpha)
                : checkerboard(anatomy[p], functional[static_cast<std::size_t>(stage)][p], greyLo,
                               greyHi);
      const int x = kLabel + c * cellW + (cellW - panel.cols) / 2;
      const int y = kLabel + r * cellH + (cellH - panel.rows) / 2;
      panel.copyTo(canvas(cv::Rect(x, y, panel.cols, panel.rows)));
      if (r == 0) label(canvas, kPlanes[p].name, {kLabel + c * cellW + 4, kLabel - 6});
    }
    // Row names run up the left margin.
    cv::Mat text(kLabel, cellH, CV_8UC3, cv::Scalar(0, 0, 0));
    label(text, rowNames[static_cast<std::size_t>(r)], {4, kLabel - 6});
    cv::Mat turned;
    cv::rotate(text, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
    turned.copyTo(canvas(cv::Rect(0, kLabel + r * cellH, kLabel, cellH)));
  }

  Image image(canvas.cols, canvas.rows);
  for (int j = 0; j < canvas.rows; ++j)
    for (int i = 0; i < canvas.cols; ++i) {
      const auto& bgr = canvas.at<cv::Vec3b>(j, i);
      std::uint8_t* out = image.pixel(i, j);
      out[0] = bgr[2];
      out[1] = bgr[1];
      out[2] = bgr[0];
      out[3] = 255;
    }
  return image;
}

}  // namespace mvw::resampling
