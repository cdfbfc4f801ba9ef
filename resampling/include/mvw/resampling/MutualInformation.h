#pragma once
// Mattes mutual information between a fixed volume, known at a set of sample points, and a
// moving volume sampled (trilinearly, in world mm) where a transform maps those points.
//
// As in Mattes et al. 2003 and ITK's MattesMutualInformationImageToImageMetric: the joint
// histogram uses a zero-order (box) window for the fixed value and a cubic B-spline Parzen
// window for the moving value, so the metric is a smooth function of the transform and its
// derivative is analytic. Samples mapping outside the moving volume are left out.
#include <array>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {

namespace detail {
class WorkerPool;
}

class MattesMutualInformation {
 public:
  struct Result {
    double value = 0.0;                // mutual information, nats (larger is better)
    int validSamples = 0;              // samples that mapped inside the moving volume
    std::array<double, 6> gradient{};  // d value / d (angles rad, translation mm); rigid only
    // d value / d (A row-major, t) for movingFromFixed x -> A (x - c) + c + t; affine only.
    std::array<double, 12> affineGradient{};
  };

  // fixedPoints: sample positions in the fixed world (LPS mm); fixedValues: the fixed
  // volume at those points. moving: float32, one component, every dimension at least 2.
  // Intensity ranges: the fixed values' 0.1 and 99.9 percentiles, so a few metal voxels do not
  // squeeze the tissue into one bin, and the moving volume's movingClip and 1 - movingClip
  // quantiles (see RegistrationOptions::movingRangeClip); values beyond count in the edge bins.
  MattesMutualInformation(std::vector<glm::dvec3> fixedPoints,
                          const std::vector<float>& fixedValues, Volume moving, int bins = 32,
                          int threads = 0, double movingClip = 1e-4);
  ~MattesMutualInformation();

  // The metric with the moving volume read at movingFromFixed(point).
  Result evaluate(const glm::dmat4& movingFromFixed) const;
  // The metric and its gradient for the rigid map movingFromFixed = rigidMatrix(p, centre).
  Result evaluateRigid(const RigidParameters& parameters, const glm::dvec3& centre) const;

  // The metric and its gradient for the affine map x -> A (x - centre) + centre + t, with
  // A = the linear part of movingFromFixed and t chosen so the map is movingFromFixed.
  Result evaluateAffine(const glm::dmat4& movingFromFixed, const glm::dvec3& centre) const;

  int sampleCount() const { return static_cast<int>(points_.size()); }
  int bins() const { return bins_; }

 private:
  enum class Gradient { None, Rigid, Affine };
  Result run(const glm::dmat4& movingFromFixed, Gradient gradient, const RigidParameters* rigid,
             const glm::dvec3& centre) const;

  std::vector<glm::dvec3> points_;
  std::vector<int> fixedBin_;
  Volume moving_;
  glm::dmat4 movingIndexFromWorld_{1.0};
  int bins_;
  std::shared_ptr<detail::WorkerPool> pool_;  // shared: copies of the metric evaluate in turn
  double movingMin_ = 0.0;
  double movingBinWidth_ = 1.0;
};

}  // namespace mvw::resampling
