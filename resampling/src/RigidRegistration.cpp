#include "mvw/resampling/RigidRegistration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

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

// Refuses what would give a garbage transform silently; returns component 0 as float32.
Volume checkedFloat(const Volume& v, const char* role) {
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
  Volume f = detail::firstComponentAsFloat(v);
  const float* p = f.dataAs<float>();
  float lo = p[0], hi = p[0];
  for (std::size_t i = 0; i < f.voxelCount(); ++i) {
    if (!std::isfinite(p[i]))
      throw InputError(name, std::string("the ") + role + " holds NaN or infinite values");
    lo = std::min(lo, p[i]);
    hi = std::max(hi, p[i]);
  }
  if (!(hi > lo)) throw InputError(name, std::string("the ") + role + " is constant");
  return f;
}

glm::dvec3 geometricCentre(const Volume& v) {
  return v.worldFromIndexPoint(glm::dvec3(v.dimensions() - 1) * 0.5);
}

// Intensity centroid, weighting each voxel by how far it lies above the 1st percentile, so
// the air around a head (or the zero background of a PET) weighs nothing.
glm::dvec3 centreOfMass(const Volume& v) {
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

RegistrationResult registerRigid(const Volume& fixedVolume, const Volume& movingVolume,
                                 const RegistrationOptions& options) {
  const auto start = Clock::now();
  detail::WorkerPool pool(options.threads);
  const Volume fixed = checkedFloat(fixedVolume, "fixed volume");
  Volume moving =
      checkedFloat(movingVolume, "moving volume");  // moved into the last level's metric

  std::vector<double> smoothing = options.smoothingMm;
  if (smoothing.empty()) {
    const double r = std::max(voxelSize(fixed), voxelSize(moving));
    smoothing = {2.0 * r, r, 0.0};
  }
  auto samplesAt = [&](std::size_t level) {
    if (options.samples.empty()) return 5000;
    return options.samples[std::min(level, options.samples.size() - 1)];
  };

  // The pyramid, built once: level images smoothed from the full-resolution ones (not from
  // each other, so each level's sigma is exactly the one asked for).
  std::vector<Volume> fixedLevels, movingLevels;
  for (double sigma : smoothing) {
    fixedLevels.push_back(sigma > 0 ? detail::smoothAndShrink(fixed, sigma, pool) : Volume());
    movingLevels.push_back(sigma > 0 ? detail::smoothAndShrink(moving, sigma, pool) : Volume());
  }
  auto fixedAt = [&](std::size_t l) -> const Volume& {
    return smoothing[l] > 0 ? fixedLevels[l] : fixed;
  };
  auto movingAt = [&](std::size_t l) -> const Volume& {
    return smoothing[l] > 0 ? movingLevels[l] : moving;
  };

  RegistrationResult result;
  // Initialisation on the coarsest images: centroids need no detail.
  {
    Initialisation init = options.initialisation;
    const glm::dvec3 fixedCom = centreOfMass(fixedAt(0)), movingCom = centreOfMass(movingAt(0));
    if (init == Initialisation::Automatic)
      init = insideVolume(fixedVolume, movingCom) && insideVolume(movingVolume, fixedCom)
                 ? Initialisation::WorldCoordinates
                 : Initialisation::CentreOfMass;
    glm::dvec3 centre = fixedCom, translation(0.0);
    if (init == Initialisation::CentreOfMass) translation = movingCom - fixedCom;
    if (init == Initialisation::GeometricCentre) {
      centre = geometricCentre(fixed);
      translation = geometricCentre(moving) - centre;
    }
    result.initialisation = init;
    result.initialTranslationMm = translation;
    result.parameters.translation = translation;
    result.transform =
        Transform::fromMovingFromFixed(rigidMatrix(result.parameters, centre), centre);
  }
  const glm::dvec3 centre = result.transform.centre();
  RigidParameters params = result.parameters;
  const double scale = options.rotationScaleMm;

  double firstStep = options.maxStepMm;
  for (std::size_t level = 0; level < smoothing.size(); ++level, firstStep *= 0.5) {
    const auto levelStart = Clock::now();
    const double sigma = smoothing[level];
    const Volume& fixedLevel = fixedAt(level);
    // The metric owns its moving image; each image is moved in at its last use, not copied.
    const bool last = level + 1 == smoothing.size();
    Volume movingLevel = sigma > 0 ? std::move(movingLevels[level])
                         : last    ? std::move(moving)
                                   : moving;

    // Off-grid sample points: uniform over the fixed volume's continuous index box, so no two
    // levels (and no sample and voxel centre) line up and the histogram sees no grid pattern.
    const int nSamples = samplesAt(level);
    std::mt19937_64 rng(options.seed + level);
    const glm::ivec3 fd = fixedLevel.dimensions();
    std::uniform_real_distribution<double> ux(0.0, fd.x - 1), uy(0.0, fd.y - 1), uz(0.0, fd.z - 1);
    std::vector<glm::dvec3> points(static_cast<std::size_t>(nSamples));
    std::vector<float> values(points.size());
    for (auto i = 0u; i < points.size(); ++i) {
      const glm::dvec3 index(ux(rng), uy(rng), uz(rng));
      points[i] = fixedLevel.worldFromIndexPoint(index);
      values[i] = static_cast<float>(detail::trilinear(fixedLevel.dataAs<float>(), fd, index));
    }

    LevelReport report;
    report.smoothingMm = sigma;
    report.fixedDimensions = fd;
    report.movingDimensions = movingLevel.dimensions();
    report.samples = nSamples;
    MattesMutualInformation metric(std::move(points), values, std::move(movingLevel),
                                   options.histogramBins, options.threads);

    auto current = metric.evaluateRigid(params, centre);
    report.metricStart = current.value;
    const int minimumValid = std::max(64, nSamples / 20);
    auto tooFewInside = [&](const std::string& when) {
      return InputError(nameOf(movingVolume, "moving volume"),
                        "does not overlap the fixed volume " + when + ": " +
                            std::to_string(current.validSamples) + " of " +
                            std::to_string(nSamples) + " sample points fall inside it");
    };
    if (current.validSamples < minimumValid)
      throw tooFewInside(level == 0
                             ? "after initialisation (" + toString(result.initialisation) + ")"
                             : "any more at level " + std::to_string(level + 1) +
                                   " (the coarser levels drifted away: do the volumes show "
                                   "the same anatomy?)");

    // Regular-step gradient ascent (ITK's RegularStepGradientDescent, maximising): fixed-length
    // steps along the scaled gradient, shortened whenever the gradient turns back. Unlike
    // ITK, a step that lowers the metric (or leaves the moving volume) is refused and the
    // step shortened: the analytic gradient ignores samples entering or leaving the overlap,
    // and on a thin slab (a 3-slice fMRI) following it blindly walks out of the volume.
    double step = firstStep;
    std::array<double, 6> previous{};
    bool havePrevious = false;
    while (report.iterations < options.maxIterationsPerLevel) {
      std::array<double, 6> g = current.gradient;
      for (int a = 0; a < 3; ++a) g[static_cast<std::size_t>(a)] /= scale;
      double norm = 0.0, dot = 0.0;
      for (std::size_t k = 0; k < 6; ++k) {
        norm += g[k] * g[k];
        dot += g[k] * previous[k];
      }
      norm = std::sqrt(norm);
      if (norm == 0.0) {
        report.converged = true;
        break;
      }
      if (havePrevious && dot < 0.0) step *= options.relaxation;
      if (step < options.minStepMm) {
        report.converged = true;
        break;
      }
      RigidParameters trial = params;
      for (int a = 0; a < 3; ++a)
        trial.angles[a] += step * g[static_cast<std::size_t>(a)] / norm / scale;
      for (int a = 0; a < 3; ++a)
        trial.translation[a] += step * g[static_cast<std::size_t>(a + 3)] / norm;
      ++report.iterations;
      const auto next = metric.evaluateRigid(trial, centre);
      if (next.validSamples < minimumValid || next.value < current.value) {
        step *= options.relaxation;
        ++report.rejectedSteps;
        continue;
      }
      params = trial;
      current = next;
      previous = g;
      havePrevious = true;
    }
    report.metricEnd = current.value;
    report.validSamples = current.validSamples;
    report.finalStepMm = step;
    report.seconds = secondsSince(levelStart);
    result.iterations += report.iterations;
    result.levels.push_back(report);
    if (options.progress) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "level %zu/%zu: sigma %.1f mm, %d iterations, MI %.4f -> %.4f%s, %.2f s",
                    level + 1, smoothing.size(), sigma, report.iterations, report.metricStart,
                    report.metricEnd, report.converged ? "" : " (not converged)", report.seconds);
      options.progress(line);
    }
  }

  result.parameters = params;
  result.transform = Transform::fromMovingFromFixed(rigidMatrix(params, centre), centre);
  result.converged = !result.levels.empty() && result.levels.back().converged;
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace mvw::resampling
