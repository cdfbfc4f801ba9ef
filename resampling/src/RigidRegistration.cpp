#include "mvw/resampling/RigidRegistration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>

#include "GaussianPyramid.h"
#include "Trilinear.h"
#include "WorkerPool.h"
#include "mvw/core/Error.h"
#include "mvw/resampling/MutualInformation.h"

namespace mvw::resampling {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::filesystem::path nameOf(const Volume& v, const char* role) {
  return v.metadata().sourcePath.empty() ? std::filesystem::path(role)
                                         : std::filesystem::path(v.metadata().sourcePath);
}

// Refuses what would give a garbage transform silently. Reads component 0 in place.
void checkVolume(const Volume& v, const char* role) {
  const auto name = nameOf(v, role);
  if (v.empty()) throw InputError(name, std::string("the ") + role + " is empty");
  const auto d = v.dimensions();
  // Two voxels along an axis are enough for trilinear sampling (an fMRI slab of 3 slices is
  // a real case); one means a 2-D image, where a rigid 3-D transform is undetermined.
  if (d.x < 2 || d.y < 2 || d.z < 2)
    throw InputError(name,
                     std::string("the ") + role + " is " + std::to_string(d.x) + " x " +
                         std::to_string(d.y) + " x " + std::to_string(d.z) +
                         ": registration needs a 3-D volume (at least 2 voxels along each axis)");
  const std::size_t stride = static_cast<std::size_t>(v.components());
  const auto [lo, hi] = dispatchScalar(v.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* p = v.dataAs<T>();
    double low = static_cast<double>(p[0]), high = low;
    for (std::size_t i = 0; i < v.voxelCount(); ++i) {
      const double x = static_cast<double>(p[i * stride]);
      if (!std::isfinite(x))
        throw InputError(name, std::string("the ") + role + " holds NaN or infinite values");
      low = std::min(low, x);
      high = std::max(high, x);
    }
    return std::pair{low, high};
  });
  if (!(hi > lo)) throw InputError(name, std::string("the ") + role + " is constant");
}

// Trilinear value of a single-component volume of any type at a continuous index.
double sample(const Volume& v, const glm::dvec3& index) {
  return dispatchScalar(v.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    return detail::trilinear(v.dataAs<T>(), v.dimensions(), index);
  });
}

glm::dvec3 geometricCentre(const Volume& v) {
  return v.worldFromIndexPoint(glm::dvec3(v.dimensions() - 1) * 0.5);
}

// Intensity centroid, weighting each voxel by how far it lies above the 1st percentile, so
// the air around a head (or the zero background of a PET) weighs nothing.
glm::dvec3 centreOfMass(const Volume& volume) {
  const Volume converted =
      volume.scalarType() == ScalarType::Float32 ? Volume() : detail::firstComponentAsFloat(volume);
  const Volume& v = volume.scalarType() == ScalarType::Float32 ? volume : converted;
  const float* p = v.dataAs<float>();
  const std::size_t n = v.voxelCount();
  std::vector<float> subset;
  const std::size_t stride = std::max<std::size_t>(1, n / 100000);
  for (std::size_t i = 0; i < n; i += stride) subset.push_back(p[i]);
  const auto q = subset.begin() + static_cast<long>(subset.size() / 100);
  std::nth_element(subset.begin(), q, subset.end());
  const double floor = *q;
  const auto d = v.dimensions();
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double w = p[v.linearIndex(i, j, k)] - floor;
        if (w <= 0.0) continue;
        sum += w * glm::dvec3(i, j, k);
        weight += w;
      }
  if (weight <= 0.0) return geometricCentre(v);
  return v.worldFromIndexPoint(sum / weight);
}

bool insideVolume(const Volume& v, const glm::dvec3& world) {
  const glm::dvec3 p(glm::inverse(v.worldFromIndex()) * glm::dvec4(world, 1.0));
  const glm::dvec3 d(v.dimensions());
  return p.x >= -0.5 && p.y >= -0.5 && p.z >= -0.5 && p.x <= d.x - 0.5 && p.y <= d.y - 0.5 &&
         p.z <= d.z - 0.5;
}

// The edge of a cube of the same volume as a voxel: 4 mm for a 4 mm PET, 5 mm for the
// 4 x 4 x 8 mm fMRI slab, whose 8 mm axis alone would over-smooth the other two.
double voxelSize(const Volume& v) {
  const auto s = v.spacing();
  return std::cbrt(s.x * s.y * s.z);
}

}  // namespace

std::string toString(Initialisation initialisation) {
  switch (initialisation) {
    case Initialisation::WorldCoordinates:
      return "world coordinates";
    case Initialisation::GeometricCentre:
      return "geometric centre";
    case Initialisation::CentreOfMass:
      return "centre of mass";
    case Initialisation::Automatic:
      break;
  }
  return "automatic";
}

namespace {

// One level's metric: off-grid sample points over the fixed image's continuous index box, so
// no two levels (and no sample and voxel centre) line up and the histogram sees no grid
// pattern; stratified (one uniform point in each of nSamples cells, about cubic in mm, of a
// grid of at least that many), so they cover the volume more evenly than independent draws.
// The box keeps marginMm from each face (at most a quarter of the axis, so a slab keeps
// points): see RegistrationOptions::faceMargin. The moving image is copied in (it is the
// small one).
MattesMutualInformation levelMetric(const Volume& fixedLevel, const Volume& movingLevel,
                                    int nSamples, std::uint64_t seed, double marginMm,
                                    const RegistrationOptions& options) {
  std::mt19937_64 rng(seed);
  const glm::dvec3 fullExtent(fixedLevel.dimensions() - 1);
  glm::dvec3 first(0.0);
  for (int a = 0; a < 3; ++a)
    first[a] = std::clamp(marginMm / fixedLevel.spacing()[a], 0.0, fullExtent[a] / 4.0);
  const glm::dvec3 extent = fullExtent - 2.0 * first;
  std::vector<glm::dvec3> indices;
  indices.reserve(static_cast<std::size_t>(nSamples));
  {
    // Cells chosen at random when the grid has more than nSamples.
    // Cells per mm k from nSamples over the box's volume; an axis too thin for one cell at
    // that density (a slab, a very anisotropic grid) gets one, and k is taken again over the
    // other axes, so that the grid never holds far more cells than samples.
    const glm::dvec3 mm = extent * fixedLevel.spacing();
    glm::bvec3 single(false);
    double k = 0.0;
    for (int pass = 0; pass < 3; ++pass) {
      double volume = 1.0;
      int free = 0;
      for (int a = 0; a < 3; ++a)
        if (!single[a]) {
          volume *= std::max(mm[a], 1e-12);
          ++free;
        }
      k = free == 3   ? std::cbrt(nSamples / volume)
          : free == 0 ? 0.0
                      : std::pow(nSamples / volume, 1.0 / free);
      glm::bvec3 next = single;
      for (int a = 0; a < 3; ++a) next[a] = next[a] || mm[a] * k < 1.0;
      if (next == single) break;
      single = next;
    }
    glm::ivec3 cells(1);
    for (int a = 0; a < 3; ++a)
      if (!single[a]) cells[a] = static_cast<int>(std::clamp(std::ceil(mm[a] * k), 1.0, 1e6));
    const std::size_t total = static_cast<std::size_t>(cells.x) * cells.y * cells.z;
    std::vector<std::size_t> order(total);
    for (std::size_t c = 0; c < total; ++c) order[c] = c;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const std::size_t n = std::min<std::size_t>(total, static_cast<std::size_t>(nSamples));
    for (std::size_t c = 0; c < n; ++c) {
      std::uniform_int_distribution<std::size_t> pick(c, total - 1);
      std::swap(order[c], order[pick(rng)]);
      const std::size_t cell = order[c];
      const glm::dvec3 corner(static_cast<double>(cell % static_cast<std::size_t>(cells.x)),
                              static_cast<double>(cell / static_cast<std::size_t>(cells.x) %
                                                  static_cast<std::size_t>(cells.y)),
                              static_cast<double>(cell / (static_cast<std::size_t>(cells.x) *
                                                          static_cast<std::size_t>(cells.y))));
      indices.push_back((corner + glm::dvec3(unit(rng), unit(rng), unit(rng))) * extent /
                        glm::dvec3(cells));
    }
  }
  std::uniform_real_distribution<double> ux(0.0, extent.x), uy(0.0, extent.y), uz(0.0, extent.z);
  while (indices.size() < static_cast<std::size_t>(nSamples))
    indices.push_back(glm::dvec3(ux(rng), uy(rng), uz(rng)));
  std::vector<glm::dvec3> points(indices.size());
  std::vector<float> values(points.size());
  for (auto& index : indices) index += first;
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = fixedLevel.worldFromIndexPoint(indices[i]);
    values[i] = static_cast<float>(sample(fixedLevel, indices[i]));
  }
  return MattesMutualInformation(std::move(points), values, movingLevel, options.histogramBins,
                                 options.threads, options.movingRangeClip);
}

struct Evaluation {
  double value = 0.0;
  int validSamples = 0;
  std::vector<double> gradient;  // d value / d x
};
using Objective = std::function<Evaluation(const std::vector<double>&)>;

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// Quasi-Newton (BFGS) ascent with a backtracking line search, maximising, on parameters x in
// millimetre-like units. A plain gradient method (ITK's regular-step descent, which this
// replaced) zigzags across the narrow valleys of MI, where a rotation about the head's
// centre and a shift trade off almost evenly, halves its step at each turn and stops short of
// the peak, as far from it as half a degree; BFGS learns that coupling from the gradients.
// Each step is at most firstStep long (mm at the head's surface for angles); a trial that
// does not raise the metric by a sufficient amount (Armijo), or leaves the moving volume, is
// refused and the step shortened by options.relaxation: the analytic gradient ignores
// samples entering or leaving the overlap, and on a thin slab (a 3-slice fMRI) following it
// blindly walks out of the volume. Converged when a step (taken or refused) is shorter than
// options.minStepMm. `current` is f(x) on entry and on return.
void ascend(std::vector<double>& x, Evaluation& current, const Objective& f, double firstStep,
            int minimumValid, const RegistrationOptions& options, LevelReport& report) {
  const std::size_t n = x.size();
  // h approximates the inverse of the metric's negative Hessian: the ascent direction is h g.
  std::vector<double> h(n * n, 0.0);
  auto resetTo = [&](double scale) {
    std::fill(h.begin(), h.end(), 0.0);
    for (std::size_t k = 0; k < n; ++k) h[k * n + k] = scale;
  };
  bool curvatureKnown = false;
  double lastStep = firstStep;
  {
    const double norm = std::sqrt(dot(current.gradient, current.gradient));
    if (norm > 0.0) resetTo(firstStep / norm);
  }
  while (report.iterations < options.maxIterationsPerLevel) {
    const std::vector<double>& g = current.gradient;
    const double gradientNorm = std::sqrt(dot(g, g));
    if (gradientNorm == 0.0) {
      report.converged = true;
      break;
    }
    std::vector<double> d(n, 0.0);
    auto direction = [&] {
      for (std::size_t i = 0; i < n; ++i) {
        d[i] = 0.0;
        for (std::size_t j = 0; j < n; ++j) d[i] += h[i * n + j] * g[j];
      }
      return dot(g, d);
    };
    double slope = direction();
    if (!(slope > 0.0)) {  // the model lost its way: start again along the gradient
      resetTo(std::max(lastStep, options.minStepMm) / gradientNorm);
      curvatureKnown = false;
      slope = direction();
    }
    double length = std::sqrt(dot(d, d));
    if (length > firstStep) {
      for (double& v : d) v *= firstStep / length;
      slope *= firstStep / length;
      length = firstStep;
    }
    double alpha = 1.0;
    bool accepted = false;
    std::vector<double> trial(n);
    Evaluation next;
    while (report.iterations < options.maxIterationsPerLevel &&
           alpha * length >= options.minStepMm) {
      for (std::size_t k = 0; k < n; ++k) trial[k] = x[k] + alpha * d[k];
      ++report.iterations;
      next = f(trial);
      if (next.validSamples >= minimumValid && next.value >= current.value + 1e-4 * alpha * slope) {
        accepted = true;
        break;
      }
      ++report.rejectedSteps;
      alpha *= options.relaxation;
    }
    lastStep = alpha * length;
    if (!accepted && curvatureKnown && report.iterations < options.maxIterationsPerLevel) {
      // The model's direction led nowhere: try once more along the plain gradient.
      resetTo(firstStep / gradientNorm);
      curvatureKnown = false;
      continue;
    }
    if (!accepted) {
      report.converged = lastStep < options.minStepMm;
      break;
    }
    // BFGS update with s = the step and y = the fall of the gradient along it.
    std::vector<double> step(n), y(n);
    for (std::size_t k = 0; k < n; ++k) {
      step[k] = alpha * d[k];
      y[k] = g[k] - next.gradient[k];
    }
    const double sy = dot(step, y);
    if (sy > 1e-12 * std::sqrt(dot(step, step) * dot(y, y))) {
      if (!curvatureKnown) resetTo(sy / dot(y, y));
      curvatureKnown = true;
      std::vector<double> hy(n, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) hy[i] += h[i * n + j] * y[j];
      const double rho = 1.0 / sy, yhy = dot(y, hy);
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          h[i * n + j] += -rho * (step[i] * hy[j] + hy[i] * step[j]) +
                          (rho * rho * yhy + rho) * step[i] * step[j];
    }
    x = trial;
    current = std::move(next);
    if (lastStep < options.minStepMm) {
      report.converged = true;
      break;
    }
  }
  report.metricEnd = current.value;
  report.validSamples = current.validSamples;
  report.finalStepMm = lastStep;
}

// Rigid parameters as optimiser coordinates: angles x scale (mm at the head's surface), mm.
std::vector<double> rigidCoordinates(const RigidParameters& p, double scale) {
  return {p.angles.x * scale, p.angles.y * scale, p.angles.z * scale,
          p.translation.x,    p.translation.y,    p.translation.z};
}
RigidParameters rigidFromCoordinates(const std::vector<double>& x, double scale) {
  return {{x[0] / scale, x[1] / scale, x[2] / scale}, {x[3], x[4], x[5]}};
}

// Affine coordinates: A row-major x scale (a change of 1 moves a point `scale` mm from the
// centre by about 1 mm, as for the angles), then t, for x -> A (x - c) + c + t.
std::vector<double> affineCoordinates(const glm::dmat4& m, const glm::dvec3& centre, double scale) {
  std::vector<double> x(12);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) x[static_cast<std::size_t>(3 * r + c)] = m[c][r] * scale;
  const glm::dvec3 t = glm::dvec3(m * glm::dvec4(centre, 1.0)) - centre;
  for (int r = 0; r < 3; ++r) x[static_cast<std::size_t>(9 + r)] = t[r];
  return x;
}
glm::dmat4 affineFromCoordinates(const std::vector<double>& x, const glm::dvec3& centre,
                                 double scale) {
  glm::dmat3 a(1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[c][r] = x[static_cast<std::size_t>(3 * r + c)] / scale;
  glm::dmat4 m(a);
  m[3] = glm::dvec4(centre + glm::dvec3(x[9], x[10], x[11]) - a * centre, 1.0);
  return m;
}

}  // namespace

namespace {

// The largest distance, over the corners of a volume's box, between where two maps put them.
double largestDisplacementMm(const Volume& v, const glm::dmat4& a, const glm::dmat4& b) {
  const glm::dvec3 last(v.dimensions() - 1);
  double largest = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 index((corner & 1) ? last.x : 0.0, (corner & 2) ? last.y : 0.0,
                           (corner & 4) ? last.z : 0.0);
    const glm::dvec4 p(v.worldFromIndexPoint(index), 1.0);
    largest = std::max(largest, glm::length(glm::dvec3(a * p) - glm::dvec3(b * p)));
  }
  return largest;
}

// The pyramid, built once: level images smoothed from the full-resolution ones (not from each
// other, so each level's sigma is exactly the one asked for). The fixed image is used as
// stored (no full-resolution float copy of a CT); a multi-component one is reduced to its
// first component. Holds a reference into itself: neither copied nor moved.
class Pyramid {
 public:
  Pyramid(const Volume& fixedVolume, const Volume& movingVolume, const RegistrationOptions& options,
          detail::WorkerPool& pool)
      : options_(options),
        fixedFirst_(fixedVolume.components() == 1 ? Volume()
                                                  : detail::firstComponentAsFloat(fixedVolume)),
        fixed_(fixedVolume.components() == 1 ? fixedVolume : fixedFirst_),
        moving_(detail::firstComponentAsFloat(movingVolume)),
        smoothing_(options.smoothingMm),
        fixedVoxel_(voxelSize(fixed_)),
        movingVoxel_(voxelSize(moving_)) {
    if (smoothing_.empty()) {
      const double r = std::max(voxelSize(fixed_), voxelSize(moving_));
      smoothing_ = {2.0 * r, r, 0.0};
    }
    for (double sigma : smoothing_) {
      fixedSigma_.push_back(sigma > 0 ? sigma : matching(fixedVoxel_));
      movingSigma_.push_back(sigma > 0 ? sigma : matching(movingVoxel_));
      fixedLevels_.push_back(fixedSigma_.back() > 0
                                 ? detail::smoothAndShrink(fixed_, fixedSigma_.back(), pool)
                                 : Volume());
      movingLevels_.push_back(movingSigma_.back() > 0
                                  ? detail::smoothAndShrink(moving_, movingSigma_.back(), pool)
                                  : Volume());
    }
  }
  Pyramid(const Pyramid&) = delete;
  Pyramid& operator=(const Pyramid&) = delete;

  std::size_t levels() const { return smoothing_.size(); }
  double smoothingMm(std::size_t l) const { return smoothing_[l]; }
  // The full-resolution images (the fixed one as stored, the moving one as float).
  const Volume& fixed() const { return fixed_; }
  const Volume& moving() const { return moving_; }
  const Volume& fixedAt(std::size_t l) const {
    return fixedSigma_[l] > 0 ? fixedLevels_[l] : fixed_;
  }
  const Volume& movingAt(std::size_t l) const {
    return movingSigma_[l] > 0 ? movingLevels_[l] : moving_;
  }
  double coarserVoxel() const { return std::max(fixedVoxel_, movingVoxel_); }
  double marginAt(std::size_t l) const {
    return options_.faceMargin * std::max(smoothing_[l], std::max(fixedVoxel_, movingVoxel_));
  }
  int samplesAt(std::size_t level) const {
    if (options_.samples.empty()) return 5000;
    return options_.samples[std::min(level, options_.samples.size() - 1)];
  }

 private:
  // At a level of smoothing 0 the finer image is still smoothed to about the coarser one's
  // resolution (see RegistrationOptions::resolutionMatching).
  double matching(double ownVoxel) const {
    const double coarse = std::max(fixedVoxel_, movingVoxel_);
    if (options_.resolutionMatching <= 0.0 || ownVoxel * 1.5 > coarse) return 0.0;
    const double target = options_.resolutionMatching * coarse,
                 own = options_.resolutionMatching * ownVoxel;
    return std::sqrt(target * target - own * own);
  }

  const RegistrationOptions& options_;
  const Volume fixedFirst_;
  const Volume& fixed_;
  const Volume moving_;
  std::vector<double> smoothing_;
  const double fixedVoxel_, movingVoxel_;
  std::vector<double> fixedSigma_, movingSigma_;
  std::vector<Volume> fixedLevels_, movingLevels_;
};

// Initialisation on the coarsest images: centroids need no detail. Sets the result's
// initialisation, initial translation, parameters and transform (whose centre the later
// stages turn about).
void initialise(const Pyramid& pyramid, const Volume& fixedVolume, const Volume& movingVolume,
                const RegistrationOptions& options, RegistrationResult& result) {
  Initialisation init = options.initialisation;
  const glm::dvec3 fixedCom = centreOfMass(pyramid.fixedAt(0)),
                   movingCom = centreOfMass(pyramid.movingAt(0));
  if (init == Initialisation::Automatic)
    init = insideVolume(fixedVolume, movingCom) && insideVolume(movingVolume, fixedCom)
               ? Initialisation::WorldCoordinates
               : Initialisation::CentreOfMass;
  glm::dvec3 centre = fixedCom, translation(0.0);
  if (init == Initialisation::CentreOfMass) translation = movingCom - fixedCom;
  if (init == Initialisation::GeometricCentre) {
    centre = geometricCentre(pyramid.fixed());
    translation = geometricCentre(pyramid.moving()) - centre;
  }
  result.initialisation = init;
  result.initialTranslationMm = translation;
  result.parameters.translation = translation;
  result.transform = Transform::fromMovingFromFixed(rigidMatrix(result.parameters, centre), centre);
}

// One line per level to options.progress; `run` -1 when there is one run (or for the affine
// stage).
void reportLevel(const RegistrationOptions& options, std::size_t level, std::size_t levels,
                 const LevelReport& report, int run, int runs) {
  if (!options.progress) return;
  char prefix[32] = "";
  if (run >= 0) std::snprintf(prefix, sizeof prefix, " run %d/%d", run + 1, runs);
  char line[240];
  std::snprintf(line, sizeof line,
                "%s%s level %zu/%zu: sigma %.1f mm, %d iterations, MI %.4f -> %.4f%s, %.2f s",
                report.stage.c_str(), prefix, level + 1, levels, report.smoothingMm,
                report.iterations, report.metricStart, report.metricEnd,
                report.converged ? "" : " (not converged)", report.seconds);
  options.progress(line);
}

// What the rigid stage of one level shares with its rotation search.
struct RigidLevel {
  const Objective& rigid;
  const MattesMutualInformation& metric;
  glm::dvec3 centre;
  double scale = 1.0;
  double firstStep = 0.0;
  int minimumValid = 0;
};

// The rotation search on the first level: score a lattice of rotations about the centre
// (translation as initialised), then climb from the best few on this level and keep the
// highest. The level's count covers every candidate's climb, the end state the best one's.
void searchRotations(const RigidLevel& level, const RegistrationOptions& options,
                     std::vector<double>& x, Evaluation& current, LevelReport& report,
                     RegistrationResult& result) {
  const double scale = level.scale;
  const double range = options.rotationSearchRangeDeg * std::numbers::pi / 180.0;
  const double stepAngle = std::max(1.0, options.rotationSearchStepDeg) * std::numbers::pi / 180.0;
  const int steps = static_cast<int>(std::floor(range / stepAngle + 1e-9));
  std::vector<std::pair<double, std::vector<double>>> scored;
  for (int a = -steps; a <= steps; ++a)
    for (int b = -steps; b <= steps; ++b)
      for (int c = -steps; c <= steps; ++c) {
        std::vector<double> p = x;
        p[0] += a * stepAngle * scale;
        p[1] += b * stepAngle * scale;
        p[2] += c * stepAngle * scale;
        const auto r =
            level.metric.evaluate(rigidMatrix(rigidFromCoordinates(p, scale), level.centre));
        ++result.searchedRotations;
        if (r.validSamples >= level.minimumValid) scored.emplace_back(r.value, std::move(p));
      }
  std::sort(scored.begin(), scored.end(),
            [](const auto& l, const auto& r) { return l.first > r.first; });
  scored.resize(std::min<std::size_t>(
      scored.size(), static_cast<std::size_t>(std::max(1, options.rotationSearchCandidates))));
  double best = -1.0;
  int iterations = 0, rejected = 0;
  for (const auto& candidate : scored) {
    std::vector<double> p = candidate.second;
    Evaluation e = level.rigid(p);
    LevelReport climb = report;
    ascend(p, e, level.rigid, level.firstStep, level.minimumValid, options, climb);
    iterations += climb.iterations;
    rejected += climb.rejectedSteps;
    if (e.value > best) {
      best = e.value;
      x = std::move(p);
      current = std::move(e);
      report.metricEnd = climb.metricEnd;
      report.validSamples = climb.validSamples;
      report.finalStepMm = climb.finalStepMm;
      report.converged = climb.converged;
    }
  }
  report.iterations = iterations;
  report.rejectedSteps = rejected;
  if (!scored.empty()) result.searchAngles = rigidFromCoordinates(x, scale).angles;
}

// One level of one rigid run: x from the previous level's end to this level's. `blamed`: the
// volume an overlap error names.
LevelReport rigidLevel(const Pyramid& pyramid, std::size_t level, std::uint64_t runSeed,
                       double firstStep, const RegistrationOptions& options, const Volume& blamed,
                       std::vector<double>& x, RegistrationResult& result) {
  const auto levelStart = Clock::now();
  const glm::dvec3 centre = result.transform.centre();
  const double scale = options.rotationScaleMm;
  const Volume& fixedLevel = pyramid.fixedAt(level);
  const int nSamples = pyramid.samplesAt(level);
  const MattesMutualInformation metric =
      levelMetric(fixedLevel, pyramid.movingAt(level), nSamples, runSeed + level,
                  pyramid.marginAt(level), options);
  const Objective rigid = [&](const std::vector<double>& p) {
    const auto r = metric.evaluateRigid(rigidFromCoordinates(p, scale), centre);
    Evaluation e{r.value, r.validSamples,
                 std::vector<double>(r.gradient.begin(), r.gradient.end())};
    for (int a = 0; a < 3; ++a) e.gradient[static_cast<std::size_t>(a)] /= scale;
    return e;
  };

  LevelReport report;
  report.smoothingMm = pyramid.smoothingMm(level);
  report.fixedDimensions = fixedLevel.dimensions();
  report.movingDimensions = pyramid.movingAt(level).dimensions();
  report.samples = nSamples;
  const int minimumValid = std::max(64, nSamples / 20);

  Evaluation current = rigid(x);
  report.metricStart = current.value;
  if (level == 0 && options.rotationSearchRangeDeg > 0.0)
    searchRotations({rigid, metric, centre, scale, firstStep, minimumValid}, options, x, current,
                    report, result);
  if (current.validSamples < minimumValid) {
    const std::string when = level == 0
                                 ? "after initialisation (" + toString(result.initialisation) + ")"
                                 : "any more at level " + std::to_string(level + 1) +
                                       " (the coarser levels drifted away: do the volumes "
                                       "show the same anatomy?)";
    throw InputError(nameOf(blamed, "moving volume"),
                     "does not overlap the fixed volume " + when + ": " +
                         std::to_string(current.validSamples) + " of " + std::to_string(nSamples) +
                         " sample points fall inside it");
  }
  if (!(level == 0 && result.searchedRotations > 0))
    ascend(x, current, rigid, firstStep, minimumValid, options, report);
  report.seconds = secondsSince(levelStart);
  return report;
}

// A later run's level added into the first run's (iterations and seconds summed, the metrics
// summed to be averaged, the worst of the rest).
void mergeLevel(LevelReport& merged, const LevelReport& report) {
  merged.iterations += report.iterations;
  merged.rejectedSteps += report.rejectedSteps;
  merged.metricStart += report.metricStart;
  merged.metricEnd += report.metricEnd;
  merged.validSamples = std::min(merged.validSamples, report.validSamples);
  merged.finalStepMm = std::max(merged.finalStepMm, report.finalStepMm);
  merged.converged = merged.converged && report.converged;
  merged.seconds += report.seconds;
}

// The rigid stage, `runs` times with their own points; the coordinates averaged. Averaged are
// the runs that ended within the coarser voxel size (anywhere in the fixed box) of the one
// with the highest metric: a run caught on another optimum is left out. Returns the averaged
// coordinates and fills the result's levels, runs and iterations.
std::vector<double> rigidRuns(const Pyramid& pyramid, const std::vector<double>& initial,
                              const RegistrationOptions& options, const Volume& blamed,
                              RegistrationResult& result) {
  const glm::dvec3 centre = result.transform.centre();
  const double scale = options.rotationScaleMm;
  const int runs = std::max(1, options.runs);
  std::vector<double> x = initial;
  std::vector<std::vector<double>> ends;
  std::vector<double> endMetric;
  for (int run = 0; run < runs; ++run) {
    x = initial;
    result.searchedRotations = 0;
    std::vector<LevelReport> runLevels;
    const std::uint64_t runSeed = options.seed + 7919ull * static_cast<std::uint64_t>(run);
    double firstStep = options.maxStepMm;
    for (std::size_t level = 0; level < pyramid.levels(); ++level, firstStep *= 0.5) {
      const LevelReport report =
          rigidLevel(pyramid, level, runSeed, firstStep, options, blamed, x, result);
      result.iterations += report.iterations;
      reportLevel(options, level, pyramid.levels(), report, runs > 1 ? run : -1, runs);
      runLevels.push_back(report);
      if (run == 0)
        result.levels.push_back(report);
      else
        mergeLevel(result.levels[level], report);
    }
    ends.push_back(x);
    endMetric.push_back(runLevels.back().metricEnd);
  }
  const std::size_t best = static_cast<std::size_t>(
      std::max_element(endMetric.begin(), endMetric.end()) - endMetric.begin());
  const glm::dmat4 bestMatrix = rigidMatrix(rigidFromCoordinates(ends[best], scale), centre);
  std::vector<double> sum(x.size(), 0.0);
  int averaged = 0;
  for (const std::vector<double>& end : ends) {
    const glm::dmat4 m = rigidMatrix(rigidFromCoordinates(end, scale), centre);
    if (largestDisplacementMm(pyramid.fixed(), m, bestMatrix) > pyramid.coarserVoxel()) continue;
    for (std::size_t k = 0; k < x.size(); ++k) sum[k] += end[k];
    ++averaged;
  }
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = sum[k] / averaged;
  for (LevelReport& level : result.levels) {
    level.metricStart /= runs;
    level.metricEnd /= runs;
  }
  result.runs = runs;
  result.runsAveraged = averaged;
  return x;
}

// The second stage: all 12 parameters, from the rigid result, on the finest levels with the
// same sample points as the rigid stage had there.
void affineStage(const Pyramid& pyramid, const glm::dvec3& centre,
                 const RegistrationOptions& options, const Volume& blamed,
                 RegistrationResult& result) {
  const double scale = options.rotationScaleMm;
  glm::dmat4 m = result.transform.movingFromFixed();
  std::vector<double> y = affineCoordinates(m, centre, scale);
  const std::size_t levels = pyramid.levels();
  const std::size_t first =
      levels -
      std::min<std::size_t>(levels, static_cast<std::size_t>(std::max(1, options.affineLevels)));
  for (std::size_t level = first; level < levels; ++level) {
    const auto levelStart = Clock::now();
    const Volume& fixedLevel = pyramid.fixedAt(level);
    const int nSamples = pyramid.samplesAt(level);
    const MattesMutualInformation metric =
        levelMetric(fixedLevel, pyramid.movingAt(level), nSamples, options.seed + level,
                    pyramid.marginAt(level), options);
    const Objective affine = [&](const std::vector<double>& p) {
      const auto r = metric.evaluateAffine(affineFromCoordinates(p, centre, scale), centre);
      Evaluation e{r.value, r.validSamples,
                   std::vector<double>(r.affineGradient.begin(), r.affineGradient.end())};
      for (int k = 0; k < 9; ++k) e.gradient[static_cast<std::size_t>(k)] /= scale;
      return e;
    };
    LevelReport report;
    report.stage = "affine";
    report.smoothingMm = pyramid.smoothingMm(level);
    report.fixedDimensions = fixedLevel.dimensions();
    report.movingDimensions = pyramid.movingAt(level).dimensions();
    report.samples = nSamples;
    Evaluation current = affine(y);
    report.metricStart = current.value;
    const double step = options.maxStepMm * std::pow(0.5, static_cast<double>(level + 1));
    ascend(y, current, affine, step, std::max(64, nSamples / 20), options, report);
    report.seconds = secondsSince(levelStart);
    result.iterations += report.iterations;
    result.levels.push_back(report);
    reportLevel(options, level, levels, report, -1, 1);
  }
  m = affineFromCoordinates(y, centre, scale);
  if (std::abs(glm::determinant(glm::dmat3(m))) < 1e-3)
    throw InputError(nameOf(blamed, "moving volume"),
                     "the affine stage collapsed the volume (determinant near 0)");
  result.affine = true;
  result.transform = Transform::fromMovingFromFixed(m, centre);
  result.converged = result.levels.back().converged;
}

// The registration with the sample points in fixedVolume. `blamed`: the volume an overlap or
// collapse error names (the caller's moving volume, whichever role it has here).
RegistrationResult registerOneWay(const Volume& fixedVolume, const Volume& movingVolume,
                                  const RegistrationOptions& options, const Volume& blamed) {
  const auto start = Clock::now();
  detail::WorkerPool pool(options.threads);
  const Pyramid pyramid(fixedVolume, movingVolume, options, pool);

  RegistrationResult result;
  initialise(pyramid, fixedVolume, movingVolume, options, result);
  const glm::dvec3 centre = result.transform.centre();
  const double scale = options.rotationScaleMm;

  const std::vector<double> x =
      rigidRuns(pyramid, rigidCoordinates(result.parameters, scale), options, blamed, result);
  result.parameters = rigidFromCoordinates(x, scale);
  result.transform = Transform::fromMovingFromFixed(rigidMatrix(result.parameters, centre), centre);
  result.converged = !result.levels.empty() && result.levels.back().converged;

  if (options.affine) affineStage(pyramid, centre, options, blamed, result);
  result.seconds = secondsSince(start);
  return result;
}

// The box a volume's voxels span, mm^3.
double boxVolumeMm3(const Volume& v) {
  const glm::dvec3 mm = glm::dvec3(v.dimensions()) * v.spacing();
  return mm.x * mm.y * mm.z;
}

}  // namespace

RegistrationResult registerRigid(const Volume& fixedVolume, const Volume& movingVolume,
                                 const RegistrationOptions& options) {
  checkVolume(fixedVolume, "fixed volume");
  checkVolume(movingVolume, "moving volume");
  if (!(options.samplePointsInSmallerVolume &&
        boxVolumeMm3(movingVolume) < 0.5 * boxVolumeMm3(fixedVolume)))
    return registerOneWay(fixedVolume, movingVolume, options, movingVolume);
  // The roles swapped: the sample points lie in the moving volume, the fixed one is read at
  // their images, and the result is inverted (centre: the swapped one's, in the fixed world).
  RegistrationResult r = registerOneWay(movingVolume, fixedVolume, options, movingVolume);
  const glm::dvec3 swappedCentre = r.transform.centre();
  const glm::dvec3 centre = r.transform.movingFromFixedPoint(swappedCentre);
  const glm::dmat4 rigidStage = glm::inverse(rigidMatrix(r.parameters, swappedCentre));
  r.transform = Transform(r.transform.movingFromFixed(), centre);
  r.parameters = rigidParameters(rigidStage, centre);
  r.initialTranslationMm = -r.initialTranslationMm;
  if (r.searchedRotations > 0)
    r.searchAngles =
        rigidParameters(glm::dmat4(glm::transpose(eulerRotation(r.searchAngles))), glm::dvec3(0.0))
            .angles;
  for (LevelReport& level : r.levels) std::swap(level.fixedDimensions, level.movingDimensions);
  r.samplesInMoving = true;
  return r;
}

}  // namespace mvw::resampling
