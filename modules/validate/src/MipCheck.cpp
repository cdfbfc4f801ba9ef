#include "mvw/validate/MipCheck.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include <glm/glm.hpp>

#include "Format.h"
#include "mvw/core/Error.h"
#include "mvw/render/Framing.h"
#include "mvw/validate/ImageMetrics.h"

namespace mvw::validate {

namespace fs = std::filesystem;
using nlohmann::json;

using detail::fmt;

MipPlan planMip(const Volume& v, const CheckSpec& c, const fs::path& suite,
                const std::string& where) {
  const glm::dmat3 dir = v.direction();
  const glm::dvec3 col = dir[c.axis];
  int w = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(col[k]) > std::abs(col[w])) w = k;
  if (std::abs(col[w]) < 0.9999)
    throw InputError(suite, where + ": the volume's index axis " + "ijk"[c.axis] +
                                " is oblique to the LPS axes; "
                                "mip_equals_max_projection needs an axis-aligned one");
  render::CameraSettings cs;
  cs.view = w == 0   ? render::StandardView::Left
            : w == 1 ? render::StandardView::Anterior
                     : render::StandardView::Superior;
  const glm::ivec3 d = v.dimensions();
  const glm::dvec3 sp = v.spacing();
  // The renderer's own framing, so the rays fall on the voxel columns.
  const render::FramingSphere framing = render::framingSphere(v);
  const glm::dvec3 centre = framing.centre;
  const double radius = framing.radius;
  const render::Camera probe = render::makeCamera(cs, centre, radius, {1, 1});
  auto along = [&](const glm::dvec3& s) {
    for (int k = 0; k < 3; ++k)
      if (k != c.axis && std::abs(glm::dot(dir[k], s)) > 0.9999) return k;
    return -1;
  };
  MipPlan p;
  p.a = along(probe.right);
  p.b = along(probe.up);
  if (p.a < 0 || p.b < 0)
    throw InputError(suite, where + ": the volume's in-plane axes are oblique to the view");
  const double pixelMm = std::min(sp[p.a], sp[p.b]);
  p.size = {static_cast<int>(std::max(1L, std::lround(d[p.a] * sp[p.a] / pixelMm))),
            static_cast<int>(std::max(1L, std::lround(d[p.b] * sp[p.b] / pixelMm)))};
  if (p.size.x > 8192 || p.size.y > 8192)
    throw InputError(suite, where + ": the volume needs a " + std::to_string(p.size.x) + " x " +
                                std::to_string(p.size.y) + " image (more than 8192 pixels a side)");
  const double aspect = static_cast<double>(p.size.x) / p.size.y;
  cs.zoom = radius / std::min(1.0, aspect) / (0.5 * p.size.y * pixelMm);
  p.camera = render::makeCamera(cs, centre, radius, p.size);
  p.view = {{"name", "render"},      {"mode", "mip"},      {"view", render::toString(cs.view)},
            {"width", p.size.x},     {"height", p.size.y}, {"zoom", cs.zoom},
            {"step_mm", sp[c.axis]}, {"jitter", false},    {"sampling", "nearest"},
            {"annotate", false}};
  if (c.window) {
    p.view["window"] = *c.window;
    p.view["level"] = *c.level;
  }
  return p;
}

CheckResult evaluateMip(const Volume& v, const CheckSpec& c, const MipPlan& p,
                        const cv::Mat& rendered, cv::Mat& expectedOut, cv::Mat& heatOut) {
  CheckResult r;
  const glm::ivec3 d = v.dimensions();
  double lo = 0, hi = 0;
  if (c.window) {
    lo = *c.level - 0.5 * *c.window;
    hi = *c.level + 0.5 * *c.window;
  } else {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          const double x = v.value(i, j, k);
          if (std::isnan(x)) continue;
          lo = std::min(lo, x);
          hi = std::max(hi, x);
        }
    if (!(hi > lo)) hi = lo + 1.0;
  }
  cv::Mat expected(p.size.y, p.size.x, CV_8U, cv::Scalar(0));
  cv::Mat delta(p.size.y, p.size.x, CV_8U, cv::Scalar(0));
  const glm::dmat4 indexFromWorld = glm::inverse(v.worldFromIndex());
  double se = 0;
  for (int row = 0; row < p.size.y; ++row)
    for (int col = 0; col < p.size.x; ++col) {
      const glm::dvec2 ndc((col + 0.5) / p.size.x * 2 - 1, 1 - (row + 0.5) / p.size.y * 2);
      const glm::dvec4 w = p.camera.worldFromClip * glm::dvec4(ndc, 0.0, 1.0);
      const glm::dvec3 idx = glm::dvec3(indexFromWorld * glm::dvec4(glm::dvec3(w) / w.w, 1.0));
      const long ia = std::lround(idx[p.a]), ib = std::lround(idx[p.b]);
      if (ia < 0 || ib < 0 || ia >= d[p.a] || ib >= d[p.b]) continue;
      // A pixel centre on a voxel boundary may go either way in the GL's nearest lookup.
      auto ambiguous = [](double f) { return std::abs(f - std::floor(f) - 0.5) < 0.02; };
      const bool sure = !ambiguous(idx[p.a]) && !ambiguous(idx[p.b]);
      double m = -std::numeric_limits<double>::infinity();
      glm::ivec3 ijk(0);
      ijk[p.a] = static_cast<int>(ia);
      ijk[p.b] = static_cast<int>(ib);
      for (int t = 0; t < d[c.axis]; ++t) {
        ijk[c.axis] = t;
        const double x = v.value(ijk.x, ijk.y, ijk.z);
        if (!std::isnan(x)) m = std::max(m, x);
      }
      const double e = std::clamp((m - lo) / (hi - lo), 0.0, 1.0) * 255.0;
      const double got = rendered.at<cv::Vec3b>(row, col)[2];  // red
      expected.at<std::uint8_t>(row, col) = static_cast<std::uint8_t>(std::lround(e));
      const double err = std::abs(got - e);
      delta.at<std::uint8_t>(row, col) =
          static_cast<std::uint8_t>(std::min(255.0, std::round(err)));
      se += err * err;
      ++r.pixels;
      if (sure) {
        ++r.unambiguous;
        r.worst = std::max(r.worst, err);
      }
    }
  expectedOut = expected;
  heatOut = heatMap(delta);
  if (r.pixels == 0) {
    r.message = "no pixel of the render falls on the volume";
    return r;
  }
  r.psnr = psnrFromMse(se / r.pixels);
  r.pass = r.psnr >= c.minPsnr && r.worst <= c.maxWorst;
  r.message = "MIP along " + std::string(1, "ijk"[c.axis]) + " vs the maximum projection: PSNR " +
              fmt(r.psnr, 2) + " dB (min " + fmt(c.minPsnr, 1) + "), worst " + fmt(r.worst, 1) +
              "/255 (max " + fmt(c.maxWorst, 1) + ") over " + std::to_string(r.unambiguous) +
              " of " + std::to_string(r.pixels) + " pixels";
  return r;
}

}  // namespace mvw::validate
