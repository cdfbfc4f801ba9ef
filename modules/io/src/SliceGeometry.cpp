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
#include <optional>
#include <string>

#include <glm/geometric.hpp>

#include "FileChecks.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

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

// The stack's in-plane directions (unit) and pixel sizes, and the slice normal (unit, on the
// side of the reader's slice axis).
struct StackAxes {
  glm::dvec3 u, v, normal;
  double su = 0.0, sv = 0.0;
};

// nullopt when the matrix gives no usable plane (the stack is then kept as it is).
std::optional<StackAxes> stackAxes(const glm::dmat4& w) {
  glm::dvec3 u(w[0]), v(w[1]);
  const double su = glm::length(u), sv = glm::length(v);
  if (!(su > 0.0) || !(sv > 0.0)) return std::nullopt;
  u /= su;
  v /= sv;
  glm::dvec3 normal = glm::cross(u, v);
  if (!(glm::length(normal) > 1e-6)) return std::nullopt;
  normal = glm::normalize(normal);
  if (glm::dot(normal, glm::dvec3(w[2])) < 0.0) normal = -normal;
  return StackAxes{u, v, normal, su, sv};
}

// The slices sorted along the normal with each one's offset from the first (in g), the
// distances between neighbours and what they say about the stack.
struct SliceOffsets {
  Grid g;
  glm::dvec3 first;
  bool tilted = false;  // a slice is off the normal through the first one
  double shiftMm = 0.0;
  std::vector<double> gaps;
  SliceSpacing ss;
  double tol = 0.0;  // distances this close to the median are equal
  bool sortedAlready = false;
};

SliceOffsets sliceOffsets(const std::vector<glm::dvec3>& positions, const StackAxes& a) {
  const int n = static_cast<int>(positions.size());
  SliceOffsets o;
  Grid& g = o.g;
  g.order.resize(n);
  std::iota(g.order.begin(), g.order.end(), 0);
  std::stable_sort(g.order.begin(), g.order.end(), [&](int l, int r) {
    return glm::dot(positions[l], a.normal) < glm::dot(positions[r], a.normal);
  });
  o.first = positions[g.order[0]];
  g.c.resize(n);
  g.du.resize(n);
  g.dv.resize(n);
  for (int r = 0; r < n; ++r) {
    const glm::dvec3 d = positions[g.order[r]] - o.first;
    g.c[r] = glm::dot(d, a.normal);
    g.du[r] = glm::dot(d, a.u) / a.su;
    g.dv[r] = glm::dot(d, a.v) / a.sv;
    o.tilted |=
        std::abs(g.du[r]) > kInPlaneTolerancePixels || std::abs(g.dv[r]) > kInPlaneTolerancePixels;
    o.shiftMm = std::max(o.shiftMm, std::hypot(g.du[r] * a.su, g.dv[r] * a.sv));
  }
  o.gaps.resize(n - 1);
  for (int r = 0; r + 1 < n; ++r) o.gaps[r] = g.c[r + 1] - g.c[r];
  SliceSpacing& ss = o.ss;
  ss.slices = n;
  std::vector<double> sorted = o.gaps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  ss.nominal = sorted[sorted.size() / 2];
  ss.minimum = *std::min_element(o.gaps.begin(), o.gaps.end());
  ss.maximum = *std::max_element(o.gaps.begin(), o.gaps.end());
  o.tol = std::max(0.01, 0.01 * ss.nominal);
  ss.regular = ss.maximum - ss.nominal <= o.tol && ss.nominal - ss.minimum <= o.tol;
  o.sortedAlready = std::is_sorted(g.order.begin(), g.order.end());
  return o;
}

// The reader's matrix can disagree with the positions it was given (vtk-dicom, without a
// usable ImageOrientationPatient, stacks slices 1 mm apart from the origin): where it does,
// the positions place the slices of a regular stack.
void placeByPositions(Volume& stack, const SliceOffsets& o, const glm::dvec3& normal) {
  const SliceSpacing& ss = o.ss;
  glm::dmat4 m = stack.worldFromIndex();
  const double along = glm::length(glm::dvec3(m[2]));
  if (std::abs(along - ss.nominal) > o.tol || glm::length(glm::dvec3(m[3]) - o.first) > 0.01) {
    m[2] = glm::dvec4(normal * ss.nominal, 0.0);
    m[3] = glm::dvec4(o.first, 1.0);
    stack.setWorldFromIndex(m);
    stack.metadata().notes.push_back("slices placed by their positions, " + fmt(ss.nominal) +
                                     " mm apart along the normal (the reader had " + fmt(along) +
                                     " mm)");
  }
}

// The grid's slice distance: the smallest that occurs, not below a quarter of the median
// (one pair of near-duplicate slices must not multiply the volume) and with at most eight
// grid planes per acquired slice; then adjusted (by less than half a step) so the first and
// last acquired slices lie on grid planes. `spacing` > 0 is taken as it is. `why` says which.
double gridStep(const SliceOffsets& o, double spacing, std::string& why) {
  const int n = static_cast<int>(o.g.c.size());
  const double extent = o.g.c.back();
  double step = spacing;
  if (step > 0.0) {
    why = "as configured";
    return step;
  }
  double smallest = std::numeric_limits<double>::infinity();
  for (double gap : o.gaps)
    if (gap > kSamePositionMm) smallest = std::min(smallest, gap);
  step = smallest;
  why = "the smallest distance";
  if (step < o.ss.nominal / 4.0) {
    step = o.ss.nominal / 4.0;
    why = "the smallest distance " + fmt(smallest) + " mm capped at a quarter of the median";
  }
  if (extent / step > 8.0 * n) {
    step = extent / (8.0 * n);
    why = "capped at eight grid planes per acquired slice";
  }
  const double steps = std::max(1.0, std::round(extent / step));
  if (std::abs(extent / steps - step) > 1e-6) why += ", adjusted to end on the last slice";
  return extent / steps;
}

// The grid's in-plane extent: the slices' pixel lattice, grown to cover every slice's
// footprint when the stack is tilted (else the offsets are rounding noise, zeroed so pixels
// stay exact).
void gridExtent(Grid& g, bool tilted, const glm::ivec3& dims, double planes) {
  const int n = static_cast<int>(g.c.size());
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
}

// Notes on uneven distances: runs of equal distances, in acquisition order along the normal
// (slices numbered 1..n), and gaps that are missing slices.
void noteUnevenSlices(std::vector<std::string>& notes, const SliceOffsets& o,
                      const std::vector<glm::dvec3>& positions) {
  const std::vector<double>& gaps = o.gaps;
  const int n = static_cast<int>(positions.size());
  std::string runs;
  int shown = 0;
  for (int a = 0; a + 1 < n;) {
    int b = a + 1;
    while (b + 1 < n && std::abs(gaps[b] - gaps[a]) <= o.tol) ++b;
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
    notes.push_back("gap of " + fmt(gaps[r]) + " mm after slice " + std::to_string(r + 1) + " of " +
                    std::to_string(n) + " (at " + lpsText(positions[o.g.order[r]]) + "): about " +
                    countOf(missing, "slice") + " missing");
  }
}

// Notes on the resampling: uneven distances, slices at one position, the order, the grid's
// slice distance (`why` it was chosen) and gantry tilt (`fill`: the value outside the slices).
void noteResampling(std::vector<std::string>& notes, const SliceOffsets& o, const StackAxes& a,
                    const std::vector<glm::dvec3>& positions, const std::string& why, double fill) {
  const Grid& g = o.g;
  const std::vector<double>& gaps = o.gaps;
  const int n = static_cast<int>(positions.size());
  if (!o.ss.regular) noteUnevenSlices(notes, o, positions);
  for (int r = 0, listed = 0; r + 1 < n && listed < 4; ++r)
    if (gaps[r] <= kSamePositionMm) {
      ++listed;
      notes.push_back("slices " + std::to_string(r + 1) + " and " + std::to_string(r + 2) + " of " +
                      std::to_string(n) + " lie at the same position (" +
                      lpsText(positions[g.order[r]]) + "): the first one's pixels are used");
    }
  if (!o.sortedAlready) notes.push_back("slices reordered by their position along the normal");
  notes.push_back("resampled along the normal onto " + fmt(g.step) + " mm (" + why +
                  "): " + std::to_string(n) + " acquired slices -> " + std::to_string(g.dims.z) +
                  ", linear between the two acquired neighbours");
  if (o.tilted) {
    const glm::dvec3 last = positions[g.order[n - 1]] - o.first;
    const double inPlane = std::hypot(g.du[n - 1] * a.su, g.dv[n - 1] * a.sv);
    const double degrees =
        std::atan2(inPlane, glm::dot(last, a.normal)) * 180.0 / 3.14159265358979323846;
    notes.push_back("gantry tilt " + fmt(degrees, 1) +
                    " degrees (slices off the normal through the first one by up to " +
                    fmt(o.shiftMm, 1) +
                    " mm): resampled onto an orthogonal grid (row, column, normal), in-plane "
                    "bilinear; the grid grows to " +
                    std::to_string(g.dims.x) + " x " + std::to_string(g.dims.y) +
                    " to cover every slice, outside them the lowest value " + fmt(fill, 1));
  }
}

}  // namespace

Volume placeSlices(Volume stack, const std::vector<glm::dvec3>& positions, double spacing,
                   std::size_t maxBytes, const std::filesystem::path& file) {
  const glm::ivec3 dims = stack.dimensions();
  const int n = static_cast<int>(positions.size());
  if (n < 2 || n != dims.z) return stack;
  const std::optional<StackAxes> axes = stackAxes(stack.worldFromIndex());
  if (!axes) return stack;
  SliceOffsets o = sliceOffsets(positions, *axes);
  const double extent = o.g.c.back();
  // Slices all at one position are stacks or time points (vtk-dicom's business), not geometry.
  if ((o.ss.regular && !o.tilted && o.sortedAlready) || !(o.ss.nominal > kSamePositionMm) ||
      !(extent > kSamePositionMm)) {
    if (o.ss.regular && !o.tilted && o.sortedAlready && o.ss.nominal > kSamePositionMm)
      placeByPositions(stack, o, axes->normal);
    stack.metadata().sliceSpacing = o.ss;
    return stack;
  }
  o.ss.resampled = true;

  std::string why;
  const double step = gridStep(o, spacing, why);
  const double planes = std::ceil(extent / step - 1e-6) + 1.0;
  if (!(planes <= static_cast<double>(1 << 20)))
    throw InputError(file, "slice spacing " + fmt(step) + " mm gives " + fmt(planes, 0) +
                               " slices over " + fmt(extent, 1) + " mm: choose a larger spacing");
  Grid& g = o.g;
  g.step = step;
  gridExtent(g, o.tilted, dims, planes);
  checkedVolumeBytes(file, g.dims, stack.components(), scalarSize(stack.scalarType()), maxBytes);

  const StackAxes& a = *axes;
  glm::dmat4 grid(1.0);
  grid[0] = glm::dvec4(a.u * a.su, 0.0);
  grid[1] = glm::dvec4(a.v * a.sv, 0.0);
  grid[2] = glm::dvec4(a.normal * step, 0.0);
  grid[3] = glm::dvec4(o.first + a.u * (a.su * g.i0) + a.v * (a.sv * g.j0), 1.0);
  Volume out(g.dims, stack.components(), stack.scalarType(), grid);
  out.metadata() = stack.metadata();
  const double fill = stack.valueRange().first;
  dispatchScalar(stack.scalarType(), [&](auto t) {
    using T = decltype(t);
    resample<T>(stack, g, fill, out);
  });
  noteResampling(out.metadata().notes, o, a, positions, why, fill);
  out.metadata().sliceSpacing = o.ss;
  return out;
}

}  // namespace mvw::io::detail
