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

// One output row of a pass across rows (y or z): out[0..n) = sum over t of kernel[t] times
// the input row at clamp(centre + t) of `count` rows, each n floats, in `rows`.
void blendRows(float* out, long n, const std::vector<float>& kernel, int centre, int count,
               const float* rows) {
  const int radius = static_cast<int>(kernel.size() / 2);
  std::fill(out, out + n, 0.0f);
  for (int t = -radius; t <= radius; ++t) {
    const float w = kernel[static_cast<std::size_t>(t + radius)];
    const float* row = rows + static_cast<long>(std::clamp(centre + t, 0, count - 1)) * n;
    for (long i = 0; i < n; ++i) out[i] += w * row[i];
  }
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
  const glm::ivec3 dims = image.dimensions();
  glm::ivec3 shrink(1), outDims = dims;
  std::vector<float> kernels[3];
  bool any = false;
  for (int axis = 0; axis < 3; ++axis) {
    // Capped at a quarter of the axis: smoothing a slab of 3 slices with a sigma of 2 slices
    // would erase the only structure that axis has.
    const double sigmaVoxels = std::min(sigmaMm / spacing[axis], (dims[axis] - 1) / 4.0);
    if (sigmaVoxels < 0.5) continue;
    shrink[axis] = std::max(1, static_cast<int>(std::floor(sigmaVoxels)));
    // Keep at least 4 voxels along the axis where there were: a coarse level that is one
    // voxel thick would leave that axis undetermined.
    while (shrink[axis] > 1 && (dims[axis] - 1) / shrink[axis] + 1 < 4) --shrink[axis];
    outDims[axis] = (dims[axis] - 1) / shrink[axis] + 1;
    kernels[axis] = gaussianKernel(sigmaVoxels);
    any = true;
  }
  if (!any) return firstComponentAsFloat(image);  // nothing to smooth
  glm::dmat4 worldFromIndex = image.worldFromIndex();
  for (int axis = 0; axis < 3; ++axis) worldFromIndex[axis] *= static_cast<double>(shrink[axis]);
  Volume out(outDims, 1, ScalarType::Float32, worldFromIndex);
  out.metadata() = image.metadata();

  // The x and y passes slice by slice (one slice of scratch per task), into the output when z
  // is not shrunk (then smoothed there in place), else into a buffer of the xy-shrunk size:
  // at most the output and that buffer exist at once, never a full-resolution float copy.
  const long nx = dims.x, ny = dims.y, nz = dims.z, ox = outDims.x, oy = outDims.y;
  const bool zInPlace = shrink.z == 1;
  std::vector<float> xyBuffer(zInPlace ? 0 : static_cast<std::size_t>(ox * oy * nz));
  float* xy = zInPlace ? out.dataAs<float>() : xyBuffer.data();
  dispatchScalar(image.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* in = image.dataAs<T>();
    pool.parallelFor(static_cast<std::size_t>(nz), [&](std::size_t slice) {
      const long k = static_cast<long>(slice);
      std::vector<float> xPassed(static_cast<std::size_t>(ox * ny));
      for (long j = 0; j < ny; ++j) {
        const T* row = in + (k * ny + j) * nx;
        float* o = xPassed.data() + j * ox;
        if (kernels[0].empty()) {
          for (long i = 0; i < nx; ++i) o[i] = static_cast<float>(row[i]);
          continue;
        }
        const int radius = static_cast<int>(kernels[0].size() / 2);
        for (long i = 0; i < ox; ++i) {
          float sum = 0.0f;
          for (int t = -radius; t <= radius; ++t)
            sum += kernels[0][static_cast<std::size_t>(t + radius)] *
                   static_cast<float>(row[std::clamp(static_cast<int>(i) * shrink.x + t, 0,
                                                     static_cast<int>(nx) - 1)]);
          o[i] = sum;
        }
      }
      float* dst = xy + k * oy * ox;
      if (kernels[1].empty()) {
        std::copy(xPassed.begin(), xPassed.end(), dst);
        return;
      }
      for (long j = 0; j < oy; ++j)
        blendRows(dst + j * ox, ox, kernels[1], static_cast<int>(j) * shrink.y,
                  static_cast<int>(ny), xPassed.data());
    });
  });
  if (kernels[2].empty()) return out;

  // The z pass, one xz plane at a time (a copy of the plane's input column by column).
  const long oz = outDims.z;
  float* result = out.dataAs<float>();
  pool.parallelFor(static_cast<std::size_t>(oy), [&](std::size_t plane) {
    const long j = static_cast<long>(plane);
    std::vector<float> column(static_cast<std::size_t>(nz * ox));
    for (long k = 0; k < nz; ++k)
      std::copy(xy + (k * oy + j) * ox, xy + (k * oy + j + 1) * ox, column.data() + k * ox);
    for (long k = 0; k < oz; ++k)
      blendRows(result + (k * oy + j) * ox, ox, kernels[2], static_cast<int>(k) * shrink.z,
                static_cast<int>(nz), column.data());
  });
  return out;
}

}  // namespace mvw::resampling::detail
