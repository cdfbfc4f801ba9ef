#include "mvw/resampling/PetPhantom.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <glm/common.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/trigonometric.hpp>

#include "mvw/core/Check.h"
#include "mvw/resampling/Resample.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {

namespace {

// Separable Gaussian, sigma in mm, zero outside the volume. v: float32, one component.
void blur(Volume& v, double sigmaMm) {
  const glm::ivec3 d = v.dimensions();
  const glm::dvec3 s = v.spacing();
  float* p = v.dataAs<float>();
  std::vector<float> line;
  for (int axis = 0; axis < 3; ++axis) {
    const double sv = sigmaMm / s[axis];
    const int r = static_cast<int>(std::ceil(3 * sv));
    std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
    double sum = 0;
    for (int t = -r; t <= r; ++t)
      sum += k[static_cast<std::size_t>(t + r)] = std::exp(-0.5 * t * t / (sv * sv));
    for (auto& w : k) w /= sum;
    const int n = d[axis];
    const std::size_t stride = axis == 0   ? 1
                               : axis == 1 ? static_cast<std::size_t>(d.x)
                                           : static_cast<std::size_t>(d.x) * d.y;
    line.resize(static_cast<std::size_t>(n));
    const glm::ivec3 other = axis == 0   ? glm::ivec3(1, d.y, d.z)
                             : axis == 1 ? glm::ivec3(d.x, 1, d.z)
                                         : glm::ivec3(d.x, d.y, 1);
    for (int c = 0; c < other.z; ++c)
      for (int b = 0; b < other.y; ++b)
        for (int a = 0; a < other.x; ++a) {
          float* base = p + v.linearIndex(a, b, c);
          for (int x = 0; x < n; ++x) line[static_cast<std::size_t>(x)] = base[x * stride];
          for (int x = 0; x < n; ++x) {
            double acc = 0;
            for (int t = std::max(-r, -x); t <= std::min(r, n - 1 - x); ++t)
              acc += k[static_cast<std::size_t>(t + r)] * line[static_cast<std::size_t>(x + t)];
            base[x * stride] = static_cast<float>(acc);
          }
        }
  }
}

Volume uptakeFromCt(const Volume& ct, double fwhmMm) {
  Volume u(ct.dimensions(), 1, ScalarType::Float32, ct.worldFromIndex());
  const glm::ivec3 d = ct.dimensions();
  float* p = u.dataAs<float>();
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const double hu = ct.value(i, j, k);
        double v = 0.0;
        if (hu >= 600)
          v = 0.25;
        else if (hu >= 150)
          v = 1.0 - 0.75 * (hu - 150) / 450;
        else if (hu >= -100)
          v = 1.0;
        else if (hu >= -500)
          v = 0.8 * (hu + 500) / 400;
        p[u.linearIndex(i, j, k)] = static_cast<float>(v);
      }
  // Hot lesions near the middle of the head, where the CT's brain is.
  const glm::dvec3 mid = ct.worldFromIndexPoint(glm::dvec3(d - 1) * 0.5);
  for (const auto& [offset, radius] :
       {std::pair{glm::dvec3(25, 15, 20), 9.0}, std::pair{glm::dvec3(-20, -25, 5), 7.0}}) {
    const glm::dvec3 centre = mid + offset;
    // worldFromIndexPoint's own arithmetic, inlined: this loop visits every CT voxel.
    const glm::dmat4& world = ct.worldFromIndex();
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i)
          if (glm::length(glm::dvec3(world * glm::dvec4(i, j, k, 1.0)) - centre) < radius)
            p[u.linearIndex(i, j, k)] = 4.0f;
  }
  blur(u, fwhmMm / 2.3548);
  return u;
}

}  // namespace

PetPhantom::PetPhantom(const Volume& ct, double fwhmMm) : uptake_(uptakeFromCt(ct, fwhmMm)) {
  const glm::ivec3 d = ct.dimensions();
  centre_ = ct.worldFromIndexPoint(glm::dvec3(d - 1) * 0.5);
  for (int k = 0; k < d.z; k += 7)
    for (int j = 0; j < d.y; j += 10)
      for (int i = 0; i < d.x; i += 10)
        if (ct.value(i, j, k) >= -300) lattice_.push_back(ct.worldFromIndexPoint({i, j, k}));
}

Volume PetPhantom::pet(const glm::dmat4& petFromCt, unsigned seed,
                       const PetGridOptions& options) const {
  MVW_CHECK(options.voxelMm > 0.0 && options.noise >= 0.0);
  const double v = options.voxelMm;
  const glm::ivec3 dims(glm::round(glm::dvec3(256.0, 256.0, 176.0) / v));
  const glm::dvec3 middle =
      options.followHead ? glm::dvec3(petFromCt * glm::dvec4(centre_, 1.0)) : centre_;
  const glm::dvec3 origin = middle - v * glm::dvec3(dims - 1) * 0.5;
  const Grid grid{dims, makeWorldFromIndex(origin, {v, v, v}, glm::dmat3(1.0))};
  // resample reads the source (CT world) at fixedFromMoving^-1 = ctFromPet of each PET voxel:
  // with the PET as resample's "fixed" grid, petFromCt is its fixedFromMoving.
  ResampleOptions linear;
  linear.interpolation = Interpolation::Linear;
  Volume pet = resample(uptake_, grid, Transform(petFromCt), linear);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  float* p = pet.dataAs<float>();
  for (std::size_t n = 0; n < pet.voxelCount(); ++n)
    p[n] = static_cast<float>(
        std::max(0.0, p[n] + options.noise * std::sqrt(std::max<double>(p[n], 0.0)) * gauss(rng) +
                          0.1 * options.noise * gauss(rng)));
  pet.metadata().modality = "PT";
  return pet;
}

double PetPhantom::meanTre(const glm::dmat4& estimatedPetFromCt,
                           const glm::dmat4& truePetFromCt) const {
  MVW_CHECK(!lattice_.empty());
  double sum = 0;
  for (const glm::dvec3& x : lattice_)
    sum += glm::length(glm::dvec3(estimatedPetFromCt * glm::dvec4(x, 1.0)) -
                       glm::dvec3(truePetFromCt * glm::dvec4(x, 1.0)));
  return sum / static_cast<double>(lattice_.size());
}

Volume petPhantomVolume(const Volume& ct, const glm::dvec3& rotateDeg, const glm::dvec3& shiftMm,
                        unsigned seed) {
  const PetPhantom phantom(ct);
  RigidParameters p;
  p.angles = glm::radians(rotateDeg);
  p.translation = shiftMm;
  Volume pet = phantom.pet(rigidMatrix(p, phantom.centre()), seed);
  pet.metadata().seriesDescription = "mvw PET-like phantom";
  return pet;
}

}  // namespace mvw::resampling
