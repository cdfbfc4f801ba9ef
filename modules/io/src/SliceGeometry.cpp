// Slice placement for DICOM stacks (vtk-dicom's vtkDICOMCTRectifier handles only uniform
// spacing, so this is done here).
//
// Uneven distances, missing slices and gantry tilt are resampled onto a regular ORTHOGONAL
// grid (row direction, column direction, slice normal) rather than described by a sheared
// index-to-world matrix: every consumer of a Volume (the ray caster's texture mapping, MPR,
// registration, the NIfTI/MetaImage writers and other tools reading their output) assumes
// orthogonal columns, and a shear silently mis-places anatomy in each one that does not.
// Along the normal each grid plane is interpolated linearly between the two acquired slices
// that bracket it; in-plane, each slice is sampled bilinearly at the grid's pixel positions,
// which follows the per-slice shift of a tilted stack. The in-plane grid keeps the slices'
// pixel lattice and grows to cover every slice's footprint.
#include "SliceGeometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>

#include "FileChecks.h"
#include "mvw/core/Error.h"

namespace mvw::io::detail {

namespace {

// Positions closer than this (pixel units in-plane, mm along the normal) are the same: real
// headers carry rounding noise of about 1e-6 mm.
constexpr double kInPlaneTolerancePixels = 0.01;
constexpr double kSamePositionMm = 1e-4;

std::string fmt(double v, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// A contiguous-pixel view of one slice of the stack: value at (x, y) by bilinear
// interpolation, half a pixel of edge extension, nothing beyond.
template <class T>
struct SliceSampler {
  const T* data;
  int nx, ny, components;
  bool sample(double x, double y, int c, double* out) const {
    if (!(x >= -0.5 && x <= nx - 0.5 && y >= -0.5 && y <= ny - 0.5)) return false;
    const double xc = std::clamp(x, 0.0, nx - 1.0), yc = std::clamp(y, 0.0, ny - 1.0);
    const int x0 = std::min(static_cast<int>(xc), std::max(nx - 2, 0));
    const int y0 = std::min(static_cast<int>(yc), std::max(ny - 2, 0));
    const double fx = xc - x0, fy = yc - y0;
    auto at = [&](int i, int j) {
      return static_cast<double>(
          data[(static_cast<std::size_t>(j) * nx + static_cast<std::size_t>(i)) * components + c]);
    };
    // Zero weights are skipped, so a slice on a grid point is copied exactly (and a NaN
    // neighbour does not leak in through 0 * NaN).
    auto row = [&](int j) {
      const double a = at(x0, j);
      return fx == 0.0 ? a : a * (1.0 - fx) + at(x0 + 1, j) * fx;
    };
    const double r0 = row(y0);
    *out = fy == 0.0 ? r0 : r0 * (1.0 - fy) + row(y0 + 1) * fy;
    return true;
  }
};

template <class T>
T toType(double v) {
  if constexpr (std::is_integral_v<T>) {
    if (std::isnan(v)) return T{0};
    const double r = std::round(v);
    return static_cast<T>(std::clamp(r, static_cast<double>(std::numeric_limits<T>::lowest()),
                                     static_cast<double>(std::numeric_limits<T>::max())));
  } else {
    return static_cast<T>(v);
  }
}

struct Grid {
  int i0 = 0, j0 = 0;  // grid pixel (0,0) in slice-0 pixel units
  glm::ivec3 dims{0};
  double step = 0.0;              // mm between grid planes
  std::vector<double> c, du, dv;  // per sorted slice: normal position, in-plane shift
  std::vector<int> order;         // sorted slice -> stack slice
};

template <class T>
void resample(const Volume& stack, const Grid& g, double fill, Volume& out) {
  const glm::ivec3 in = stack.dimensions();
  const int comps = stack.components();
  const std::size_t sliceValues = static_cast<std::size_t>(in.x) * in.y * comps;
  const T* src = stack.dataAs<T>();
  T* dst = out.dataAs<T>();
  const int n = static_cast<int>(g.c.size());
  auto sampler = [&](int r) {
    return SliceSampler<T>{src + static_cast<std::size_t>(g.order[r]) * sliceValues, in.x, in.y,
                           comps};
  };
  int r = 0;
  for (int m = 0; m < g.dims.z; ++m) {
    const double p = std::min(m * g.step, g.c.back());
    while (r < n - 2 && g.c[r + 1] < p) ++r;
    const double width = g.c[r + 1] - g.c[r];
    double t = width > kSamePositionMm ? std::clamp((p - g.c[r]) / width, 0.0, 1.0) : 0.0;
    // Planes within rounding noise of an acquired slice copy it.
    if (t * width < 1e-6) t = 0.0;
    if ((1.0 - t) * width < 1e-6 && width > kSamePositionMm) t = 1.0;
    const SliceSampler<T> lo = sampler(r), hi = sampler(r + 1);
    T* plane = dst + static_cast<std::size_t>(m) * g.dims.x * g.dims.y * comps;
    for (int j = 0; j < g.dims.y; ++j)
      for (int i = 0; i < g.dims.x; ++i)
        for (int c = 0; c < comps; ++c) {
          double a = 0.0, b = 0.0;
          const bool hasA = t < 1.0 && lo.sample(g.i0 + i - g.du[r], g.j0 + j - g.dv[r], c, &a);
          const bool hasB =
              t > 0.0 && hi.sample(g.i0 + i - g.du[r + 1], g.j0 + j - g.dv[r + 1], c, &b);
          double v = fill;
          if (hasA && hasB)
            v = a * (1.0 - t) + b * t;
          else if (t <= 0.5 ? hasA : hasB)  // at a footprint's edge: the nearer slice only
            v = t <= 0.5 ? a : b;
          plane[(static_cast<std::size_t>(j) * g.dims.x + i) * comps + c] = toType<T>(v);
        }
  }
}

std::string lpsText(const glm::dvec3& p) {
  return "LPS " + fmt(p.x, 1) + ", " + fmt(p.y, 1) + ", " + fmt(p.z, 1) + " mm";
}

}  // namespace

Volume placeSlices(Volume stack, const std::vector<glm::dvec3>& positions, double spacing,
                   std::size_t maxBytes, const std::filesystem::path& file) {
  const glm::ivec3 dims = stack.dimensions();
  const int n = static_cast<int>(positions.size());
  if (n < 2 || n != dims.z) return stack;
  const glm::dmat4& w = stack.worldFromIndex();
  glm::dvec3 u(w[0]), v(w[1]);
  const double su = glm::length(u), sv = glm::length(v);
  if (!(su > 0.0) || !(sv > 0.0)) return stack;
  u /= su;
  v /= sv;
  glm::dvec3 normal = glm::cross(u, v);
  if (!(glm::length(normal) > 1e-6)) return stack;
  normal = glm::normalize(normal);
  if (glm::dot(normal, glm::dvec3(w[2])) < 0.0) normal = -normal;

  Grid g;
  g.order.resize(n);
  std::iota(g.order.begin(), g.order.end(), 0);
  std::stable_sort(g.order.begin(), g.order.end(), [&](int a, int b) {
    return glm::dot(positions[a], normal) < glm::dot(positions[b], normal);
  });
  const glm::dvec3 first = positions[g.order[0]];
  g.c.resize(n);
  g.du.resize(n);
  g.dv.resize(n);
  double shiftMm = 0.0;
  bool tilted = false;
  for (int r = 0; r < n; ++r) {
    const glm::dvec3 d = positions[g.order[r]] - first;
    g.c[r] = glm::dot(d, normal);
    g.du[r] = glm::dot(d, u) / su;
    g.dv[r] = glm::dot(d, v) / sv;
    tilted |=
        std::abs(g.du[r]) > kInPlaneTolerancePixels || std::abs(g.dv[r]) > kInPlaneTolerancePixels;
    shiftMm = std::max(shiftMm, std::hypot(g.du[r] * su, g.dv[r] * sv));
  }
  std::vector<double> gaps(n - 1);
  for (int r = 0; r + 1 < n; ++r) gaps[r] = g.c[r + 1] - g.c[r];
  SliceSpacing ss;
  ss.slices = n;
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  ss.nominal = sorted[sorted.size() / 2];
  ss.minimum = *std::min_element(gaps.begin(), gaps.end());
  ss.maximum = *std::max_element(gaps.begin(), gaps.end());
  const double tol = std::max(0.01, 0.01 * ss.nominal);
  ss.regular = ss.maximum - ss.nominal <= tol && ss.nominal - ss.minimum <= tol;
  const bool sortedAlready = std::is_sorted(g.order.begin(), g.order.end());
  const double extent = g.c.back();
  // Slices all at one position are stacks or time points (vtk-dicom's business), not geometry.
  if ((ss.regular && !tilted && sortedAlready) || !(ss.nominal > kSamePositionMm) ||
      !(extent > kSamePositionMm)) {
    // The reader's matrix can disagree with the positions it was given (vtk-dicom, without a
    // usable ImageOrientationPatient, stacks slices 1 mm apart from the origin): where it
    // does, the positions place the slices.
    if (ss.regular && !tilted && sortedAlready && ss.nominal > kSamePositionMm) {
      glm::dmat4 m = w;
      const double along = glm::length(glm::dvec3(m[2]));
      if (std::abs(along - ss.nominal) > tol || glm::length(glm::dvec3(m[3]) - first) > 0.01) {
        m[2] = glm::dvec4(normal * ss.nominal, 0.0);
        m[3] = glm::dvec4(first, 1.0);
        stack.setWorldFromIndex(m);
        stack.metadata().notes.push_back("slices placed by their positions, " + fmt(ss.nominal) +
                                         " mm apart along the normal (the reader had " +
                                         fmt(along) + " mm)");
      }
    }
    stack.metadata().sliceSpacing = ss;
    return stack;
  }
  ss.resampled = true;

  // The grid's slice distance: the smallest that occurs, not below a quarter of the median
  // (one pair of near-duplicate slices must not multiply the volume) and with at most eight
  // grid planes per acquired slice; then adjusted (by less than half a step) so the first and
  // last acquired slices lie on grid planes.
  std::string why;
  double step = spacing;
  if (step > 0.0) {
    why = "as configured";
  } else {
    double smallest = std::numeric_limits<double>::infinity();
    for (double gap : gaps)
      if (gap > kSamePositionMm) smallest = std::min(smallest, gap);
    step = smallest;
    why = "the smallest distance";
    if (step < ss.nominal / 4.0) {
      step = ss.nominal / 4.0;
      why = "the smallest distance " + fmt(smallest) + " mm capped at a quarter of the median";
    }
    if (extent / step > 8.0 * n) {
      step = extent / (8.0 * n);
      why = "capped at eight grid planes per acquired slice";
    }
    const double steps = std::max(1.0, std::round(extent / step));
    if (std::abs(extent / steps - step) > 1e-6) why += ", adjusted to end on the last slice";
    step = extent / steps;
  }
  const double planes = std::ceil(extent / step - 1e-6) + 1.0;
  if (!(planes <= static_cast<double>(1 << 20)))
    throw InputError(file, "slice spacing " + fmt(step) + " mm gives " + fmt(planes, 0) +
                               " slices over " + fmt(extent, 1) + " mm: choose a larger spacing");
  g.step = step;
  int i1 = dims.x - 1, j1 = dims.y - 1;
  if (tilted) {
    for (int r = 0; r < n; ++r) {
      g.i0 = std::min(g.i0, static_cast<int>(std::floor(g.du[r] + 1e-3)));
      g.j0 = std::min(g.j0, static_cast<int>(std::floor(g.dv[r] + 1e-3)));
      i1 = std::max(i1, static_cast<int>(std::ceil(g.du[r] + dims.x - 1 - 1e-3)));
      j1 = std::max(j1, static_cast<int>(std::ceil(g.dv[r] + dims.y - 1 - 1e-3)));
    }
  } else {
    std::fill(g.du.begin(), g.du.end(), 0.0);  // rounding noise only: keep pixels exact
    std::fill(g.dv.begin(), g.dv.end(), 0.0);
  }
  g.dims = {i1 - g.i0 + 1, j1 - g.j0 + 1, static_cast<int>(planes)};
  checkedVolumeBytes(file, g.dims, stack.components(), scalarSize(stack.scalarType()), maxBytes);

  glm::dmat4 grid(1.0);
  grid[0] = glm::dvec4(u * su, 0.0);
  grid[1] = glm::dvec4(v * sv, 0.0);
  grid[2] = glm::dvec4(normal * step, 0.0);
  grid[3] = glm::dvec4(first + u * (su * g.i0) + v * (sv * g.j0), 1.0);
  Volume out(g.dims, stack.components(), stack.scalarType(), grid);
  out.metadata() = stack.metadata();
  const double fill = stack.valueRange().first;
  dispatchScalar(stack.scalarType(), [&](auto t) {
    using T = decltype(t);
    resample<T>(stack, g, fill, out);
  });

  auto& notes = out.metadata().notes;
  if (!ss.regular) {
    // Runs of equal distances, in acquisition order along the normal (slices numbered 1..n).
    std::string runs;
    int shown = 0;
    for (int a = 0; a + 1 < n;) {
      int b = a + 1;
      while (b + 1 < n && std::abs(gaps[b] - gaps[a]) <= tol) ++b;
      if (shown++ == 6) {
        runs += ", ...";
        break;
      }
      runs += (runs.empty() ? "" : ", ") + fmt(gaps[a]) + " mm";
      if (b - a > 1) runs += " x " + std::to_string(b - a);
      runs += " (slices " + std::to_string(a + 1) + "-" + std::to_string(b + 1) + ")";
      a = b;
    }
    notes.push_back("slice distances along the normal are uneven: " + runs);
    // A gap is missing slices when it is a multiple of the distances around it (the median
    // of three on each side): a change of protocol (4 mm, then 7 mm slices) is not.
    int listed = 0;
    for (int r = 0; r + 1 < n && listed < 8; ++r) {
      std::vector<double> around;
      for (int q = std::max(0, r - 3); q <= std::min(n - 2, r + 3); ++q)
        if (q != r) around.push_back(gaps[q]);
      if (around.empty()) continue;
      std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
      const double local = around[around.size() / 2];
      if (!(local > kSamePositionMm) || gaps[r] < 1.5 * local) continue;
      ++listed;
      const long missing = std::lround(gaps[r] / local) - 1;
      notes.push_back("gap of " + fmt(gaps[r]) + " mm after slice " + std::to_string(r + 1) +
                      " of " + std::to_string(n) + " (at " + lpsText(positions[g.order[r]]) +
                      "): about " + std::to_string(missing) + " slice" + (missing == 1 ? "" : "s") +
                      " missing");
    }
  }
  for (int r = 0, listed = 0; r + 1 < n && listed < 4; ++r)
    if (gaps[r] <= kSamePositionMm) {
      ++listed;
      notes.push_back("slices " + std::to_string(r + 1) + " and " + std::to_string(r + 2) + " of " +
                      std::to_string(n) + " lie at the same position (" +
                      lpsText(positions[g.order[r]]) + "): the first one's pixels are used");
    }
  if (!sortedAlready) notes.push_back("slices reordered by their position along the normal");
  notes.push_back("resampled along the normal onto " + fmt(step) + " mm (" + why +
                  "): " + std::to_string(n) + " acquired slices -> " + std::to_string(g.dims.z) +
                  ", linear between the two acquired neighbours");
  if (tilted) {
    const glm::dvec3 last = positions[g.order[n - 1]] - first;
    const double inPlane = std::hypot(g.du[n - 1] * su, g.dv[n - 1] * sv);
    const double degrees =
        std::atan2(inPlane, glm::dot(last, normal)) * 180.0 / 3.14159265358979323846;
    notes.push_back("gantry tilt " + fmt(degrees, 1) +
                    " degrees (slices off the normal through the first one by up to " +
                    fmt(shiftMm, 1) +
                    " mm): resampled onto an orthogonal grid (row, column, normal), in-plane "
                    "bilinear; the grid grows to " +
                    std::to_string(g.dims.x) + " x " + std::to_string(g.dims.y) +
                    " to cover every slice, outside them the lowest value " + fmt(fill, 1));
  }
  out.metadata().sliceSpacing = ss;
  return out;
}

}  // namespace mvw::io::detail
