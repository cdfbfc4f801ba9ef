#include "GaussianPyramid.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "WorkerPool.h"
#include "mvw/core/Check.h"

namespace mvw::resampling::detail {

namespace {

std::vector<float> gaussianKernel(double sigmaVoxels) {
  const int radius = std::max(1, static_cast<int>(std::ceil(3.0 * sigmaVoxels)));
  std::vector<float> k(static_cast<std::size_t>(2 * radius + 1));
  double sum = 0.0;
  for (int t = -radius; t <= radius; ++t) {
    const double w = std::exp(-0.5 * t * t / (sigmaVoxels * sigmaVoxels));
    k[static_cast<std::size_t>(t + radius)] = static_cast<float>(w);
    sum += w;
  }
  for (auto& w : k) w = static_cast<float>(w / sum);
  return k;
}

// One separable pass along `axis`: out[.., o, ..] = sum_t k[t] in[.., clamp(s*o + t), ..].
// Borders replicate the edge voxel, so a volume's outer intensity does not fade to zero.
template <typename T>
std::vector<float> pass(const T* in, glm::ivec3 dims, int axis, const std::vector<float>& kernel,
                        int shrink, glm::ivec3& outDims, WorkerPool& pool) {
  const int radius = static_cast<int>(kernel.size() / 2);
  outDims = dims;
  outDims[axis] = (dims[axis] - 1) / shrink + 1;
  const long nx = dims.x, ny = dims.y;
  const long ox = outDims.x, oy = outDims.y, oz = outDims.z;
  std::vector<float> out(static_cast<std::size_t>(ox * oy * oz), 0.0f);
  const int n = dims[axis];
  auto clampIndex = [n](int i) { return std::clamp(i, 0, n - 1); };
  pool.parallelFor(static_cast<std::size_t>(oz), [&](std::size_t slice) {
    const long k = static_cast<long>(slice);
    for (long j = 0; j < oy; ++j) {
      float* o = out.data() + (k * oy + j) * ox;
      if (axis == 0) {
        const T* row = in + (k * ny + j) * nx;
        for (long i = 0; i < ox; ++i) {
          float sum = 0.0f;
          for (int t = -radius; t <= radius; ++t)
            sum += kernel[static_cast<std::size_t>(t + radius)] *
                   static_cast<float>(row[clampIndex(static_cast<int>(i) * shrink + t)]);
          o[i] = sum;
        }
      } else {
        // Whole rows at a time along x: contiguous reads even for the y and z passes.
        for (int t = -radius; t <= radius; ++t) {
          const float w = kernel[static_cast<std::size_t>(t + radius)];
          const long src = axis == 1 ? clampIndex(static_cast<int>(j) * shrink + t) : j;
          const long srcK = axis == 2 ? clampIndex(static_cast<int>(k) * shrink + t) : k;
          const T* row = in + (srcK * ny + src) * nx;
          for (long i = 0; i < ox; ++i) o[i] += w * static_cast<float>(row[i]);
        }
      }
    }
  });
  return out;
}

}  // namespace

Volume firstComponentAsFloat(const Volume& volume) {
  Volume out(volume.dimensions(), 1, ScalarType::Float32, volume.worldFromIndex());
  float* dst = out.dataAs<float>();
  const std::size_t stride = static_cast<std::size_t>(volume.components());
  dispatchScalar(volume.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* src = volume.dataAs<T>();
    for (std::size_t i = 0; i < volume.voxelCount(); ++i)
      dst[i] = static_cast<float>(src[i * stride]);
  });
  out.metadata() = volume.metadata();
  return out;
}

Volume smoothAndShrink(const Volume& image, double sigmaMm, WorkerPool& pool) {
  MVW_CHECK(image.components() == 1);
  const glm::dvec3 spacing = image.spacing();
  glm::ivec3 dims = image.dimensions();
  // The first pass reads the image in place (whatever its type): a full-resolution float
  // copy of a CT would be the largest allocation of a registration.
  std::vector<float> data;
  bool first = true;
  glm::ivec3 shrink(1);
  for (int axis = 0; axis < 3; ++axis) {
    // Capped at a quarter of the axis: smoothing a slab of 3 slices with a sigma of 2 slices
    // would erase the only structure that axis has.
    const double sigmaVoxels = std::min(sigmaMm / spacing[axis], (dims[axis] - 1) / 4.0);
    if (sigmaVoxels < 0.5) continue;
    shrink[axis] = std::max(1, static_cast<int>(std::floor(sigmaVoxels)));
    // Keep at least 4 voxels along the axis where there were: a coarse level that is one
    // voxel thick would leave that axis undetermined.
    while (shrink[axis] > 1 && (dims[axis] - 1) / shrink[axis] + 1 < 4) --shrink[axis];
    glm::ivec3 outDims;
    const auto kernel = gaussianKernel(sigmaVoxels);
    if (first)
      data = dispatchScalar(image.scalarType(), [&](auto zero) {
        using T = decltype(zero);
        return pass(image.dataAs<T>(), dims, axis, kernel, shrink[axis], outDims, pool);
      });
    else
      data = pass(data.data(), dims, axis, kernel, shrink[axis], outDims, pool);
    first = false;
    dims = outDims;
  }
  glm::dmat4 worldFromIndex = image.worldFromIndex();
  for (int axis = 0; axis < 3; ++axis) worldFromIndex[axis] *= static_cast<double>(shrink[axis]);
  if (first) return firstComponentAsFloat(image);  // nothing to smooth
  Volume out(dims, 1, ScalarType::Float32, worldFromIndex);
  std::copy(data.begin(), data.end(), out.dataAs<float>());
  out.metadata() = image.metadata();
  return out;
}

}  // namespace mvw::resampling::detail
