#include "mvw/resampling/MutualInformation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_inverse.hpp>

#include "Trilinear.h"
#include "WorkerPool.h"
#include "mvw/core/Check.h"

namespace mvw::resampling {

namespace {

// Bins kept free at each end of the histogram so the cubic B-spline window (support 4 bins)
// of a value at the range's edge still fits, as in ITK.
constexpr int kPadding = 2;

double bspline3(double u) {
  u = std::abs(u);
  if (u < 1.0) return (4.0 - 6.0 * u * u + 3.0 * u * u * u) / 6.0;
  if (u < 2.0) return (2.0 - u) * (2.0 - u) * (2.0 - u) / 6.0;
  return 0.0;
}

double bspline3Derivative(double u) {
  const double a = std::abs(u);
  if (a < 1.0) return -2.0 * u + 1.5 * u * a;
  if (a < 2.0) return (u > 0 ? -0.5 : 0.5) * (2.0 - a) * (2.0 - a);
  return 0.0;
}

// The q and 1-q percentiles of `values` (a copy is partially sorted).
std::pair<double, double> robustRange(std::vector<float> values, double q) {
  MVW_CHECK(!values.empty());
  const auto n = values.size();
  const auto lo = static_cast<std::size_t>(q * static_cast<double>(n - 1));
  const auto hi = static_cast<std::size_t>((1.0 - q) * static_cast<double>(n - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(lo), values.end());
  const double a = values[lo];
  std::nth_element(values.begin(), values.begin() + static_cast<long>(hi), values.end());
  return {a, values[hi]};
}

}  // namespace

MattesMutualInformation::MattesMutualInformation(std::vector<glm::dvec3> fixedPoints,
                                                 const std::vector<float>& fixedValues,
                                                 Volume moving, int bins, int threads,
                                                 double movingClip)
    : points_(std::move(fixedPoints)),
      moving_(std::move(moving)),
      movingIndexFromWorld_(glm::inverse(moving_.worldFromIndex())),
      bins_(bins),
      pool_(std::make_shared<detail::WorkerPool>(threads)) {
  MVW_CHECK_EQ(points_.size(), fixedValues.size());
  MVW_CHECK(!points_.empty());
  MVW_CHECK(bins_ >= 2 * kPadding + 4);
  MVW_CHECK(moving_.scalarType() == ScalarType::Float32 && moving_.components() == 1);
  const auto d = moving_.dimensions();
  MVW_CHECK(d.x >= 2 && d.y >= 2 && d.z >= 2);
  const int usable = bins_ - 2 * kPadding;

  const auto [fixedMin, fixedMax0] = robustRange(fixedValues, 0.001);
  const double fixedWidth = std::max(fixedMax0 - fixedMin, 1e-12) / usable;
  fixedBin_.resize(fixedValues.size());
  for (std::size_t s = 0; s < fixedValues.size(); ++s) {
    const int b = static_cast<int>(std::floor((fixedValues[s] - fixedMin) / fixedWidth)) + kPadding;
    fixedBin_[s] = std::clamp(b, kPadding, bins_ - kPadding - 1);
  }

  // A strided subset of the moving voxels is plenty for two percentiles.
  const float* v = moving_.dataAs<float>();
  const std::size_t n = moving_.voxelCount();
  const std::size_t stride = std::max<std::size_t>(1, n / 200000);
  std::vector<float> subset;
  subset.reserve(n / stride + 1);
  for (std::size_t i = 0; i < n; i += stride) subset.push_back(v[i]);
  const auto [movingMin, movingMax] =
      robustRange(std::move(subset), std::clamp(movingClip, 0.0, 0.49));
  movingMin_ = movingMin;
  movingBinWidth_ = std::max(movingMax - movingMin, 1e-12) / usable;
}

MattesMutualInformation::~MattesMutualInformation() = default;

MattesMutualInformation::Result MattesMutualInformation::evaluate(
    const glm::dmat4& movingFromFixed) const {
  return run(movingFromFixed, Gradient::None, nullptr, glm::dvec3(0.0));
}

MattesMutualInformation::Result MattesMutualInformation::evaluateAffine(
    const glm::dmat4& movingFromFixed, const glm::dvec3& centre) const {
  return run(movingFromFixed, Gradient::Affine, nullptr, centre);
}

MattesMutualInformation::Result MattesMutualInformation::evaluateRigid(
    const RigidParameters& parameters, const glm::dvec3& centre) const {
  return run(rigidMatrix(parameters, centre), Gradient::Rigid, &parameters, centre);
}

MattesMutualInformation::Result MattesMutualInformation::run(const glm::dmat4& movingFromFixed,
                                                             Gradient gradientKind,
                                                             const RigidParameters* rigid,
                                                             const glm::dvec3& centre) const {
  const int nb = bins_;
  const std::size_t nSamples = points_.size();
  const glm::dmat4 indexFromFixed = movingIndexFromWorld_ * movingFromFixed;
  const glm::dmat3 indexFromWorldLinear(movingIndexFromWorld_);
  const glm::ivec3 dims = moving_.dimensions();
  const float* voxels = moving_.dataAs<float>();
  const bool wantGradient = gradientKind != Gradient::None;

  // Per sample: the moving value in bin units (negative: outside the moving volume) and
  // d(moving value)/d(moving world point), zero where the value was clamped to the range.
  std::vector<double> movingBin(nSamples);
  std::vector<glm::dvec3> movingGradient(wantGradient ? nSamples : 0);

  // One histogram per chunk of samples, summed in chunk order afterwards: the same numbers
  // whatever the thread count and scheduling.
  const std::size_t nChunks = std::clamp<std::size_t>(nSamples / 512, 1, 32);
  auto chunkBegin = [&](std::size_t c) { return nSamples * c / nChunks; };
  std::vector<double> partial(nChunks * static_cast<std::size_t>(nb * nb), 0.0);
  std::vector<int> partialValid(nChunks, 0);

  pool_->parallelFor(nChunks, [&](std::size_t c) {
    double* hist = partial.data() + c * static_cast<std::size_t>(nb * nb);
    int valid = 0;
    for (std::size_t s = chunkBegin(c); s < chunkBegin(c + 1); ++s) {
      const glm::dvec3 p(indexFromFixed * glm::dvec4(points_[s], 1.0));
      if (!detail::insideIndex(dims, p)) {
        movingBin[s] = -1.0;
        continue;
      }
      glm::dvec3 gradientIndex(0.0);
      const double m = detail::trilinear(voxels, dims, p, wantGradient ? &gradientIndex : nullptr);
      double bin = (m - movingMin_) / movingBinWidth_ + kPadding;
      bool clamped = false;
      if (bin < kPadding) bin = kPadding, clamped = true;
      if (bin > nb - kPadding) bin = nb - kPadding, clamped = true;
      movingBin[s] = bin;
      if (wantGradient)
        movingGradient[s] =
            clamped ? glm::dvec3(0.0) : glm::transpose(indexFromWorldLinear) * gradientIndex;
      const int pivot = std::clamp(static_cast<int>(bin), kPadding, nb - kPadding - 1);
      double* row = hist + fixedBin_[s] * nb;
      for (int j = pivot - 1; j <= pivot + 2; ++j) row[j] += bspline3(j - bin);
      ++valid;
    }
    partialValid[c] = valid;
  });

  Result result;
  std::vector<double> joint(static_cast<std::size_t>(nb * nb), 0.0);
  for (std::size_t c = 0; c < nChunks; ++c) {
    result.validSamples += partialValid[c];
    const double* hist = partial.data() + c * joint.size();
    for (std::size_t i = 0; i < joint.size(); ++i) joint[i] += hist[i];
  }
  if (result.validSamples == 0) return result;

  const double norm = 1.0 / result.validSamples;
  std::vector<double> pf(static_cast<std::size_t>(nb), 0.0), pm(static_cast<std::size_t>(nb), 0.0);
  for (int i = 0; i < nb; ++i)
    for (int j = 0; j < nb; ++j) {
      const double p = joint[static_cast<std::size_t>(i * nb + j)] * norm;
      pf[static_cast<std::size_t>(i)] += p;
      pm[static_cast<std::size_t>(j)] += p;
    }
  // log(p / (pf pm)) per bin: the MI summand and, because sum dp = 0, the weight of dp in dMI.
  std::vector<double> logRatio(joint.size(), 0.0);
  for (int i = 0; i < nb; ++i)
    for (int j = 0; j < nb; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i * nb + j);
      const double p = joint[ij] * norm;
      if (p <= 0.0) continue;
      logRatio[ij] =
          std::log(p / (pf[static_cast<std::size_t>(i)] * pm[static_cast<std::size_t>(j)]));
      result.value += p * logRatio[ij];
    }
  if (!wantGradient) return result;

  // dMI/dmu = sum_ij dp_ij/dmu log(p_ij / (pf_i pm_j)), and dp_ij/dmu collects, per sample of
  // fixed bin i, -B3'(j - bin) * dbin/dmu / N with dbin/dmu = (grad m . dx/dmu) / binWidth.
  // With x = A (p - c) + c + t, dx/dA_rc = e_r (p - c)_c: accumulating the outer product
  // w grad m (p - c)^T gives the affine gradient, and the rigid one follows from it by the
  // chain rule through dR/dangle (dx/dangle = dR/dangle (p - c)).
  std::vector<std::array<double, 12>> partialGradient(nChunks);
  pool_->parallelFor(nChunks, [&](std::size_t c) {
    std::array<double, 12> g{};
    for (std::size_t s = chunkBegin(c); s < chunkBegin(c + 1); ++s) {
      const double bin = movingBin[s];
      if (bin < 0.0) continue;
      const glm::dvec3& gw = movingGradient[s];
      if (gw.x == 0.0 && gw.y == 0.0 && gw.z == 0.0) continue;
      const int pivot = std::clamp(static_cast<int>(bin), kPadding, nb - kPadding - 1);
      const double* row = logRatio.data() + fixedBin_[s] * nb;
      double w = 0.0;
      for (int j = pivot - 1; j <= pivot + 2; ++j) w -= bspline3Derivative(j - bin) * row[j];
      const glm::dvec3 local = points_[s] - centre;
      for (int r = 0; r < 3; ++r) {
        const double wg = w * gw[r];
        for (int col = 0; col < 3; ++col)
          g[static_cast<std::size_t>(3 * r + col)] += wg * local[col];
        g[static_cast<std::size_t>(9 + r)] += wg;
      }
    }
    partialGradient[c] = g;
  });
  const double scale = norm / movingBinWidth_;
  for (std::size_t c = 0; c < nChunks; ++c)
    for (std::size_t k = 0; k < 12; ++k) result.affineGradient[k] += partialGradient[c][k] * scale;
  if (gradientKind == Gradient::Rigid) {
    for (int a = 0; a < 3; ++a) {
      const glm::dmat3 dR = eulerRotationDerivative(rigid->angles, a);
      double d = 0.0;
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col)
          d += result.affineGradient[static_cast<std::size_t>(3 * r + col)] * dR[col][r];
      result.gradient[static_cast<std::size_t>(a)] = d;
    }
    for (int a = 0; a < 3; ++a)
      result.gradient[static_cast<std::size_t>(3 + a)] =
          result.affineGradient[static_cast<std::size_t>(9 + a)];
    result.affineGradient = {};
  }
  return result;
}

}  // namespace mvw::resampling
