#include "mvw/render/Annotations.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "mvw/render/TransferFunction.h"

namespace mvw::render {

std::string orientationLabel(const glm::dvec3& w) {
  static constexpr char kToward[3][2] = {{'L', 'R'}, {'P', 'A'}, {'S', 'I'}};
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return std::abs(w[a]) > std::abs(w[b]); });
  const double len = glm::length(w);
  std::string label(1, kToward[order[0]][w[order[0]] >= 0 ? 0 : 1]);
  if (len > 0 && std::abs(w[order[1]]) / len > 0.38)
    label += kToward[order[1]][w[order[1]] >= 0 ? 0 : 1];
  return label;
}

void annotate(Image& image, const Camera& camera, const std::string& caption) {
  cv::Mat m(image.height, image.width, CV_8UC4, image.rgba.data());
  const double scale = std::max(0.4, std::min(image.width, image.height) / 600.0);
  const int thick = std::max(1, static_cast<int>(std::lround(scale * 1.5)));
  const cv::Scalar yellow(255, 230, 60, 255), black(0, 0, 0, 255);
  auto text = [&](const std::string& s, cv::Point at, double sc) {
    cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, sc, black, thick + 2, cv::LINE_AA);
    cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, sc, yellow, thick, cv::LINE_AA);
  };
  auto size = [&](const std::string& s, double sc) {
    int base = 0;
    return cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, sc, thick, &base);
  };
  const double labelScale = 0.9 * scale;
  const int pad = static_cast<int>(8 * scale);
  const std::string right = orientationLabel(camera.right), left = orientationLabel(-camera.right);
  const std::string top = orientationLabel(camera.up), bottom = orientationLabel(-camera.up);
  const int w = image.width, h = image.height;
  cv::Size sz = size(left, labelScale);
  text(left, {pad, h / 2 + sz.height / 2}, labelScale);
  sz = size(right, labelScale);
  text(right, {w - pad - sz.width, h / 2 + sz.height / 2}, labelScale);
  sz = size(top, labelScale);
  text(top, {w / 2 - sz.width / 2, pad + sz.height}, labelScale);
  sz = size(bottom, labelScale);
  text(bottom, {w / 2 - sz.width / 2, h - pad}, labelScale);

  const double captionScale = 0.5 * scale;
  // The scale bar: a round length near a quarter of the width, bottom right.
  const bool scaleBar = !camera.perspective && camera.halfHeightMm > 0;
  const double mmPerPixel = scaleBar ? 2.0 * camera.halfHeightMm / h : 0.0;
  double mm = 0.0;
  int px = 0;
  char barText[32] = "";
  if (scaleBar) {
    const double target = 0.25 * w * mmPerPixel;
    const double pow10 = std::pow(10.0, std::floor(std::log10(target)));
    mm = pow10;
    for (double f : {2.0, 5.0, 10.0})
      if (f * pow10 <= target) mm = f * pow10;
    px = static_cast<int>(std::lround(mm / mmPerPixel));
    std::snprintf(barText, sizeof barText, "%g mm", mm);
  }
  const int y = h - pad - static_cast<int>(8 * scale);
  const cv::Size barSize = size(barText, captionScale);
  if (!caption.empty()) {
    // A caption that would reach the scale bar or its length goes a line up, clear of both
    // (issue 36 item 8: a depth-cued MIP's long caption ran into the bar).
    cv::Point at(pad, h - pad - static_cast<int>(28 * scale));
    int base = 0;
    const cv::Size captionSize =
        cv::getTextSize(caption, cv::FONT_HERSHEY_SIMPLEX, captionScale, thick, &base);
    const int barLeft = w - pad - std::max(px, barSize.width);
    if (scaleBar && pad + captionSize.width + pad > barLeft)
      at.y = y - static_cast<int>(6 * scale) - barSize.height - base - thick - 2 - pad;
    text(caption, at, captionScale);
  }
  if (scaleBar) {
    const cv::Point a(w - pad - px, y), b(w - pad, y);
    cv::line(m, a, b, black, thick + 3);
    cv::line(m, a, b, yellow, thick);
    text(barText, {w - pad - barSize.width, y - static_cast<int>(6 * scale)}, captionScale);
  }
}

namespace {

// The bar in 256 colours (index 0 at the bottom), the range's ends and the unit beside it.
void drawBar(Image& image, double lo, double hi, const std::string& unit, const std::string& title,
             const std::vector<cv::Scalar>& colours) {
  cv::Mat m(image.height, image.width, CV_8UC4, image.rgba.data());
  const double scale = std::max(0.4, std::min(image.width, image.height) / 600.0);
  const int barW = std::max(6, static_cast<int>(14 * scale));
  const int top = image.height / 4, bottom = image.height * 3 / 4;
  const int x0 = image.width - barW - static_cast<int>(44 * scale), x1 = x0 + barW;
  for (int y = top; y <= bottom; ++y) {
    const cv::Scalar& c =
        colours[static_cast<std::size_t>(255.0 * (bottom - y) / std::max(1, bottom - top))];
    cv::line(m, {x0, y}, {x1, y}, c);
  }
  cv::rectangle(m, {x0 - 1, top - 1}, {x1 + 1, bottom + 1}, cv::Scalar(200, 200, 200, 255), 1);
  const double textScale = 0.4 * scale;
  const int thick = std::max(1, static_cast<int>(std::lround(scale)));
  // Each label on a dark box: readable on any background (white on an inverted-grey MIP, a
  // bright lesion under it); the box ends at the image's right edge if the text is wider.
  auto text = [&](const std::string& s, int y) {
    int baseline = 0;
    const cv::Size sz = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, textScale, thick, &baseline);
    const int x = std::max(0, std::min(x0 - 2, image.width - sz.width - 2));
    const int pad = std::max(2, static_cast<int>(3 * scale));
    cv::rectangle(m, {x - pad, y - sz.height - pad}, {x + sz.width + pad, y + baseline + pad / 2},
                  cv::Scalar(0, 0, 0, 255), cv::FILLED);
    cv::putText(m, s, {x, y}, cv::FONT_HERSHEY_SIMPLEX, textScale, cv::Scalar(255, 230, 60, 255),
                thick, cv::LINE_AA);
  };
  auto label = [&](double v, int y) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    text(buf, y);
  };
  if (!title.empty()) text(title, top - static_cast<int>(24 * scale));
  label(hi, top - static_cast<int>(6 * scale));
  label(lo, bottom + static_cast<int>(16 * scale));
  text(unit.empty() ? "no unit" : unit, bottom + static_cast<int>(32 * scale));
}

}  // namespace

void drawColourBar(Image& image, double lo, double hi, const std::string& unit,
                   const std::string& title) {
  const auto lut = sampleTransferFunction(transferPreset("pet-hot-metal"), 0.0, 1.0, 256, 0.0, 1.0);
  std::vector<cv::Scalar> colours;
  for (const glm::vec4& c : lut) colours.emplace_back(255 * c.r, 255 * c.g, 255 * c.b, 255);
  drawBar(image, lo, hi, unit, title, colours);
}

void drawColourBar(Image& image, double lo, double hi, const std::string& unit,
                   const ColorTable& table, const std::string& title) {
  std::vector<cv::Scalar> colours;
  for (const auto& c : table.rgb) colours.emplace_back(c[0], c[1], c[2], 255);
  drawBar(image, lo, hi, unit, title, colours);
}

void drawGlyphLegend(Image& image, const GlyphLegend& legend) {
  if (legend.entries.empty()) return;
  cv::Mat m(image.height, image.width, CV_8UC4, image.rgba.data());
  const double scale = std::max(0.4, std::min(image.width, image.height) / 600.0);
  const int radius = std::max(5, static_cast<int>(std::lround(12 * scale)));
  const int pad = static_cast<int>(10 * scale), row = 2 * radius + static_cast<int>(6 * scale);
  const double textScale = 0.4 * scale;
  const int thick = std::max(1, static_cast<int>(std::lround(scale)));
  const cv::Scalar yellow(255, 230, 60, 255), black(0, 0, 0, 255);
  auto text = [&](const std::string& s, cv::Point at) {
    cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, textScale, black, thick + 2, cv::LINE_AA);
    cv::putText(m, s, at, cv::FONT_HERSHEY_SIMPLEX, textScale, yellow, thick, cv::LINE_AA);
  };
  int y = pad + static_cast<int>(12 * scale);
  text(legend.title, {pad, y});
  y += static_cast<int>(8 * scale);
  const glm::dvec3 light = glm::normalize(glm::dvec3(-0.6, -0.6, 1.0));  // image y points down
  for (const GlyphLegendEntry& e : legend.entries) {
    const int cx = pad + radius, cy = y + radius;
    if (!e.icon.rgba.empty() && e.size > 0.0) {
      // The glyph as the view's shader draws it (issue 40), scaled to the icon's square.
      cv::Mat icon(e.icon.height, e.icon.width, CV_8UC4,
                   const_cast<std::uint8_t*>(e.icon.rgba.data()));
      cv::Mat scaled;
      cv::resize(icon, scaled, {2 * radius + 1, 2 * radius + 1}, 0, 0, cv::INTER_AREA);
      const cv::Rect box(cx - radius, cy - radius, 2 * radius + 1, 2 * radius + 1);
      if ((box & cv::Rect(0, 0, m.cols, m.rows)) == box) scaled.copyTo(m(box));
      text(e.label, {cx + radius + static_cast<int>(6 * scale), cy + static_cast<int>(5 * scale)});
      y += row;
      continue;
    }
    // The icon's square: mid grey, the bump shaded on it with the renderer's light direction.
    cv::rectangle(m, {cx - radius, cy - radius}, {cx + radius, cy + radius},
                  cv::Scalar(110, 110, 110, 255), cv::FILLED);
    const double r = radius * std::clamp(e.size, 0.0, 1.0);
    for (int dy = -radius; dy <= radius && r >= 0.5; ++dy)
      for (int dx = -radius; dx <= radius; ++dx) {
        const double q = (dx * dx + dy * dy) / (r * r);
        if (q > 1.0) continue;
        glm::dvec3 n(dx / r, dy / r, std::sqrt(1.0 - q));
        if (e.kind == GlyphKind::Dimples) n.x = -n.x, n.y = -n.y;
        const double shade = 255.0 * std::clamp(0.2 + 0.8 * glm::dot(n, light), 0.0, 1.0);
        auto* px = m.ptr<cv::Vec4b>(cy + dy, cx + dx);
        (*px)[0] = (*px)[1] = (*px)[2] = static_cast<unsigned char>(shade);
      }
    text(e.label, {cx + radius + static_cast<int>(6 * scale), cy + static_cast<int>(5 * scale)});
    y += row;
  }
}

}  // namespace mvw::render
