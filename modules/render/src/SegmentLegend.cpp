#include "mvw/render/SegmentLegend.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace mvw::render {

void drawSegmentLegend(Image& image, const std::vector<LegendEntry>& entries) {
  cv::Mat m(image.height, image.width, CV_8UC4, image.rgba.data());
  // The same scale as the captions of annotate() (Annotations.cpp).
  const double scale = std::max(0.4, std::min(image.width, image.height) / 600.0);
  const double textScale = 0.5 * scale;
  const int thick = std::max(1, static_cast<int>(std::lround(scale * 1.5)));
  const int pad = static_cast<int>(8 * scale), line = static_cast<int>(24 * scale);
  int y = pad + static_cast<int>(52 * scale);
  for (const auto& e : entries) {
    const cv::Scalar colour(255 * e.colour.r, 255 * e.colour.g, 255 * e.colour.b, 255);
    const int box = static_cast<int>(12 * scale);
    cv::rectangle(m, {pad, y - box}, {pad + box, y}, cv::Scalar(0, 0, 0, 255), thick + 2);
    cv::rectangle(m, {pad, y - box}, {pad + box, y}, colour, thick);
    const cv::Point at(pad + box + static_cast<int>(6 * scale), y);
    cv::putText(m, e.name, at, cv::FONT_HERSHEY_SIMPLEX, textScale, cv::Scalar(0, 0, 0, 255),
                thick + 2, cv::LINE_AA);
    cv::putText(m, e.name, at, cv::FONT_HERSHEY_SIMPLEX, textScale, colour, thick, cv::LINE_AA);
    y += line;
  }
}

}  // namespace mvw::render
