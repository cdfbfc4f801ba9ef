#include "mvw/study/RoiStatistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"

namespace mvw::study {

namespace {

std::string fmt3(const glm::dvec3& p) {
  return fixedNumber(p.x, 3) + ", " + fixedNumber(p.y, 3) + ", " + fixedNumber(p.z, 3);
}

// Component 0 of every voxel as double (NaN stays NaN).
std::vector<double> valuesOf(const Volume& volume) {
  const std::size_t n = volume.voxelCount();
  const auto c = static_cast<std::size_t>(volume.components());
  std::vector<double> out(n);
  dispatchScalar(volume.scalarType(), [&](auto t) {
    using T = decltype(t);
    const T* data = reinterpret_cast<const T*>(volume.data());
    for (std::size_t v = 0; v < n; ++v) out[v] = static_cast<double>(data[v * c]);
  });
  return out;
}

// Component 0 of a voxel as double, read in place (no copy of a large volume per ROI).
class ValueReader {
 public:
  explicit ValueReader(const Volume& volume)
      : data_(volume.data()),
        type_(volume.scalarType()),
        stride_(static_cast<std::size_t>(volume.components())) {}
  double operator[](std::size_t voxel) const {
    const std::size_t at = voxel * stride_;
    return dispatchScalar(type_, [&](auto t) {
      using T = decltype(t);
      return static_cast<double>(reinterpret_cast<const T*>(data_)[at]);
    });
  }

 private:
  const std::byte* data_;
  ScalarType type_;
  std::size_t stride_;
};

// Index-space bounding box (clamped to the volume) of a world-space axis-aligned box; false
// when it misses the volume.
bool indexBounds(const Volume& volume, const glm::dvec3& lo, const glm::dvec3& hi, glm::ivec3& from,
                 glm::ivec3& to) {
  const glm::dmat4 indexFromWorld = glm::inverse(volume.worldFromIndex());
  glm::dvec3 a(std::numeric_limits<double>::infinity()), b(-a);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 w{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                       corner & 4 ? hi.z : lo.z};
    const glm::dvec3 ijk(indexFromWorld * glm::dvec4(w, 1.0));
    a = glm::min(a, ijk);
    b = glm::max(b, ijk);
  }
  const glm::ivec3 d = volume.dimensions();
  for (int axis = 0; axis < 3; ++axis) {
    // Compared as doubles before any cast: a far-away ROI (1e300 mm) must not overflow an int.
    const double first = std::max(0.0, std::floor(a[axis]));
    const double last = std::min(static_cast<double>(d[axis] - 1), std::ceil(b[axis]));
    if (!(first <= last)) return false;
    from[axis] = static_cast<int>(first);
    to[axis] = static_cast<int>(last);
  }
  return true;
}

std::size_t spatialIndex(const glm::ivec3& d, int i, int j, int k) {
  return (static_cast<std::size_t>(k) * static_cast<std::size_t>(d.y) +
          static_cast<std::size_t>(j)) *
             static_cast<std::size_t>(d.x) +
         static_cast<std::size_t>(i);
}

std::string boundsText(const Volume& volume) {
  const glm::ivec3 d = volume.dimensions();
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 w = volume.worldFromIndexPoint(
        {corner & 1 ? d.x - 1 : 0, corner & 2 ? d.y - 1 : 0, corner & 4 ? d.z - 1 : 0});
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
  return "the voxel centres span (" + fmt3(lo) + ") .. (" + fmt3(hi) + ") mm LPS";
}

template <class Inside>
VoxelList collect(const Volume& volume, const glm::dvec3& lo, const glm::dvec3& hi, Inside&& inside,
                  const std::string& what) {
  glm::ivec3 from, to;
  VoxelList out;
  if (indexBounds(volume, lo, hi, from, to)) {
    const glm::ivec3 d = volume.dimensions();
    for (int k = from.z; k <= to.z; ++k)
      for (int j = from.y; j <= to.y; ++j)
        for (int i = from.x; i <= to.x; ++i)
          if (inside(volume.worldFromIndexPoint({i, j, k})))
            out.push_back(spatialIndex(d, i, j, k));
  }
  if (out.empty())
    throw InputError(volume.metadata().sourcePath,
                     what + " holds no voxel centre of this volume (" + boundsText(volume) + ")");
  return out;
}

}  // namespace

bool isSuvUnit(const std::string& unit) { return unit.rfind("SUV", 0) == 0; }

VoxelList sphereVoxels(const Volume& volume, const SphereRoi& s) {
  const std::string what =
      "the sphere at (" + fmt3(s.centre) + ") mm, radius " + fixedNumber(s.radiusMm, 3) + " mm,";
  if (!(s.radiusMm > 0) || !std::isfinite(s.radiusMm) || !std::isfinite(glm::length(s.centre)))
    throw InputError(volume.metadata().sourcePath,
                     "the sphere's radius must be a positive number of mm (got " +
                         fixedNumber(s.radiusMm, 3) + ")");
  const double r2 = s.radiusMm * s.radiusMm;
  const glm::dvec3 half(s.radiusMm);
  return collect(
      volume, s.centre - half, s.centre + half,
      [&](const glm::dvec3& w) {
        const glm::dvec3 d = w - s.centre;
        return glm::dot(d, d) <= r2;
      },
      what);
}

VoxelList boxVoxels(const Volume& volume, const BoxRoi& b) {
  if (!std::isfinite(glm::length(b.min)) || !std::isfinite(glm::length(b.max)))
    throw InputError(volume.metadata().sourcePath, "the box corners must be finite numbers");
  for (int a = 0; a < 3; ++a)
    if (b.min[a] > b.max[a])
      throw InputError(volume.metadata().sourcePath,
                       std::string("the box's first corner must not exceed the second: ") +
                           "LPS"[a] + " " + fixedNumber(b.min[a], 3) + " > " +
                           fixedNumber(b.max[a], 3) + " mm");
  return collect(
      volume, b.min, b.max,
      [&](const glm::dvec3& w) {
        return w.x >= b.min.x && w.x <= b.max.x && w.y >= b.min.y && w.y <= b.max.y &&
               w.z >= b.min.z && w.z <= b.max.z;
      },
      "the box (" + fmt3(b.min) + ") .. (" + fmt3(b.max) + ") mm");
}

namespace {

// valueFromLabel maps the value grid's indices into the label grid's: the grids coincide when it
// is an integer translation.
bool coincide(const glm::dmat4& labelFromValue) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (std::abs(labelFromValue[c][r] - (c == r ? 1.0 : 0.0)) > 1e-4) return false;
  for (int r = 0; r < 3; ++r)
    if (std::abs(labelFromValue[3][r] - std::round(labelFromValue[3][r])) > 1e-3) return false;
  return true;
}

// For every voxel of `volume`, the nearest voxel of `labels` (or nothing outside it).
template <class Visit>
bool forNearest(const Volume& volume, const Volume& labels, Visit&& visit) {
  const glm::dmat4 labelFromValue = glm::inverse(labels.worldFromIndex()) * volume.worldFromIndex();
  const glm::ivec3 d = volume.dimensions(), l = labels.dimensions();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const glm::dvec4 p = labelFromValue * glm::dvec4(i, j, k, 1.0);
        const long long li = std::llround(p.x), lj = std::llround(p.y), lk = std::llround(p.z);
        if (li < 0 || lj < 0 || lk < 0 || li >= l.x || lj >= l.y || lk >= l.z) continue;
        visit(spatialIndex(d, i, j, k),
              spatialIndex(l, static_cast<int>(li), static_cast<int>(lj), static_cast<int>(lk)));
      }
  return coincide(labelFromValue);
}

std::string placementNote(bool same, const Volume& labels) {
  return same ? "the label grid coincides with the volume's grid (voxel for voxel)"
              : "labels placed onto the volume's grid by world position, nearest neighbour "
                "(label grid " +
                    std::to_string(labels.dimensions().x) + " x " +
                    std::to_string(labels.dimensions().y) + " x " +
                    std::to_string(labels.dimensions().z) + ")";
}

}  // namespace

LabelPlacement placeSegmentation(const Volume& volume, const io::Segmentation& seg) {
  const std::string& mine = volume.metadata().frameOfReferenceUid;
  const std::string& theirs = seg.frameOfReferenceUid;
  if (!mine.empty() && !theirs.empty() && mine != theirs)
    throw InputError(seg.masks.metadata().sourcePath,
                     "the segmentation is on another frame of reference (" + theirs +
                         ") than the volume " + volume.metadata().sourcePath + " (" + mine + ")");
  LabelPlacement out;
  for (const auto& s : seg.segments)
    out.labels.push_back(
        {s.number, s.label.empty() ? "segment " + std::to_string(s.number) : s.label, s.rgb, {}});
  const auto c = static_cast<std::size_t>(seg.masks.components());
  const std::uint8_t* masks = seg.masks.dataAs<std::uint8_t>();
  out.gridsCoincide = forNearest(volume, seg.masks, [&](std::size_t v, std::size_t l) {
    for (std::size_t s = 0; s < c; ++s)
      if (masks[l * c + s]) out.labels[s].voxels.push_back(v);
  });
  out.note = placementNote(out.gridsCoincide, seg.masks);
  if (mine.empty() || theirs.empty())
    out.note += "; frame of reference not checked (not stated by both)";
  return out;
}

LabelPlacement placeLabelVolume(const Volume& volume, const Volume& labels) {
  const std::vector<double> values = valuesOf(labels);
  std::map<long long, std::size_t> slot;
  for (double v : values) {
    if (std::isnan(v) || v == 0.0) continue;
    if (v != std::floor(v))
      throw InputError(labels.metadata().sourcePath,
                       "not a label map: it holds the non-integer value " + shortNumber(v));
    if (std::abs(v) > 1e9) {
      char text[48];
      std::snprintf(text, sizeof text, "%.0f", v);
      throw InputError(labels.metadata().sourcePath,
                       std::string("not a label map: its label ") + text +
                           " is beyond 1e9 (label numbers are small integers)");
    }
    if (slot.emplace(static_cast<long long>(v), 0).second && slot.size() > 65535)
      throw InputError(labels.metadata().sourcePath,
                       "not a label map: more than 65535 distinct values");
  }
  if (slot.empty()) throw InputError(labels.metadata().sourcePath, "the label map holds no label");
  LabelPlacement out;
  for (auto& [label, index] : slot) {
    index = out.labels.size();
    out.labels.push_back({static_cast<int>(label), "label " + std::to_string(label), {}, {}});
  }
  out.gridsCoincide = forNearest(volume, labels, [&](std::size_t v, std::size_t l) {
    const double label = values[l];
    if (std::isnan(label) || label == 0.0) return;
    out.labels[slot[static_cast<long long>(label)]].voxels.push_back(v);
  });
  out.note = placementNote(out.gridsCoincide, labels);
  return out;
}

RoiStats roiStatistics(const Volume& volume, const VoxelList& voxels, const StatsOptions& options) {
  RoiStats out;
  out.unit = volume.metadata().unit;
  const ValueReader values(volume);
  const glm::ivec3 d = volume.dimensions();
  const glm::dmat3 linear(volume.worldFromIndex());
  const double voxelMl = std::abs(glm::determinant(linear)) / 1000.0;
  auto worldOf = [&](std::size_t v) {
    const auto nx = static_cast<std::size_t>(d.x), ny = static_cast<std::size_t>(d.y);
    return volume.worldFromIndexPoint({static_cast<double>(v % nx),
                                       static_cast<double>((v / nx) % ny),
                                       static_cast<double>(v / (nx * ny))});
  };
  // Two passes (mean, then squared deviations): exact for a uniform region.
  double sum = 0.0, maxValue = -std::numeric_limits<double>::infinity();
  std::size_t maxVoxel = 0;
  for (std::size_t v : voxels) {
    const double x = values[v];
    if (std::isnan(x)) {
      ++out.noData;
      continue;
    }
    ++out.voxels;
    sum += x;
    if (x > maxValue) {
      maxValue = x;
      maxVoxel = v;
    }
  }
  out.volumeMl = static_cast<double>(out.voxels) * voxelMl;
  if (out.voxels == 0) return out;
  out.max = maxValue;
  out.maxAt = worldOf(maxVoxel);
  out.mean = sum / static_cast<double>(out.voxels);
  double squares = 0.0;
  for (std::size_t v : voxels)
    if (!std::isnan(values[v])) squares += (values[v] - out.mean) * (values[v] - out.mean);
  out.sd = std::sqrt(squares / static_cast<double>(out.voxels));

  if (options.threshold.kind != Threshold::Kind::None) {
    const double t = options.threshold.kind == Threshold::Kind::Absolute
                         ? options.threshold.value
                         : options.threshold.value * out.max;
    out.thresholdValue = t;
    double metabolicSum = 0.0;
    for (std::size_t v : voxels)
      if (!std::isnan(values[v]) && values[v] >= t)
        ++out.metabolicVoxels, metabolicSum += values[v];
    out.metabolicVolumeMl = static_cast<double>(out.metabolicVoxels) * voxelMl;
    if (out.metabolicVoxels > 0)
      out.metabolicMean = metabolicSum / static_cast<double>(out.metabolicVoxels);
    out.tlg = metabolicSum * voxelMl;  // = metabolic volume x its mean
  }

  if (options.peak) {
    // The sphere's voxels as index offsets (the grid is the same everywhere).
    struct Offset {
      int di, dj, dk;
    };
    std::vector<Offset> kernel;
    const double r = kPeakRadiusMm;
    const int n = static_cast<int>(std::ceil(r / volume.smallestSpacing())) + 1;
    for (int dk = -n; dk <= n; ++dk)
      for (int dj = -n; dj <= n; ++dj)
        for (int di = -n; di <= n; ++di) {
          const glm::dvec3 w = linear * glm::dvec3(di, dj, dk);
          if (glm::dot(w, w) <= r * r) kernel.push_back({di, dj, dk});
        }
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t v : voxels) {
      if (std::isnan(values[v])) continue;
      const auto nx = static_cast<std::size_t>(d.x), ny = static_cast<std::size_t>(d.y);
      const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
                k = static_cast<int>(v / (nx * ny));
      double s = 0.0;
      std::size_t count = 0;
      for (const Offset& o : kernel) {
        const int a = i + o.di, b = j + o.dj, c = k + o.dk;
        if (a < 0 || b < 0 || c < 0 || a >= d.x || b >= d.y || c >= d.z) continue;
        const double x = values[spatialIndex(d, a, b, c)];
        if (std::isnan(x)) continue;
        s += x;
        ++count;
      }
      if (count == 0) continue;
      const double mean = s / static_cast<double>(count);
      if (mean > best) {
        best = mean;
        out.peakAt = worldOf(v);
        out.peakSphereVoxels = count;
      }
    }
    if (std::isfinite(best)) out.peak = best;
  }
  return out;
}

VoxelList metabolicVoxels(const Volume& volume, const VoxelList& voxels, double threshold) {
  const ValueReader values(volume);
  VoxelList out;
  for (std::size_t v : voxels)
    if (!std::isnan(values[v]) && values[v] >= threshold) out.push_back(v);
  std::sort(out.begin(), out.end());
  return out;
}

MetabolicTotal metabolicTotal(const Volume& volume, const std::vector<VoxelList>& lesions,
                              const std::vector<double>& thresholds) {
  MVW_CHECK_EQ(lesions.size(), thresholds.size());
  VoxelList all;
  for (std::size_t i = 0; i < lesions.size(); ++i) {
    const VoxelList hot = metabolicVoxels(volume, lesions[i], thresholds[i]);
    all.insert(all.end(), hot.begin(), hot.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  const ValueReader values(volume);
  const double voxelMl = std::abs(glm::determinant(glm::dmat3(volume.worldFromIndex()))) / 1000.0;
  MetabolicTotal out;
  double sum = 0.0;
  for (std::size_t v : all) sum += values[v];
  out.voxels = all.size();
  out.volumeMl = static_cast<double>(out.voxels) * voxelMl;
  if (out.voxels > 0) out.mean = sum / static_cast<double>(out.voxels);
  out.tlg = sum * voxelMl;
  return out;
}

}  // namespace mvw::study
