#include "mvw/resampling/Resample.h"

#include "mvw/io/VtkImageView.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <unordered_set>

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkImageReslice.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <glm/gtc/matrix_inverse.hpp>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"

namespace mvw::resampling {

namespace {

Volume firstComponent(const Volume& volume) {
  Volume out(volume.dimensions(), 1, volume.scalarType(), volume.worldFromIndex());
  const std::size_t size = scalarSize(volume.scalarType());
  const std::size_t stride = size * static_cast<std::size_t>(volume.components());
  const std::byte* src = volume.data();
  std::byte* dst = out.data();
  for (std::size_t i = 0; i < volume.voxelCount(); ++i)
    std::memcpy(dst + i * size, src + i * stride, size);
  out.metadata() = volume.metadata();
  return out;
}

const char* name(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::Nearest:
      return "nearest-neighbour";
    case Interpolation::Cubic:
      return "cubic";
    case Interpolation::Linear:
    case Interpolation::Automatic:
      break;
  }
  return "linear";
}

}  // namespace

Grid gridOf(const Volume& volume) { return {volume.dimensions(), volume.worldFromIndex()}; }

bool looksLikeLabelMap(const Volume& volume) {
  if (volume.empty() || !isInteger(volume.scalarType())) return false;
  const std::size_t limit = scalarSize(volume.scalarType()) == 1 ? 64 : 256;
  return dispatchScalar(volume.scalarType(), [&](auto zero) {
    using T = decltype(zero);
    const T* v = volume.dataAs<T>();
    std::unordered_set<T> seen;
    // Stops at the first value past the limit: a CT answers after a few hundred voxels.
    for (std::size_t i = 0; i < volume.valueCount(); ++i) {
      if (seen.insert(v[i]).second && seen.size() > limit) return false;
    }
    return true;
  });
}

Interpolation chosenInterpolation(const Volume& moving, const ResampleOptions& options) {
  if (options.interpolation != Interpolation::Automatic) return options.interpolation;
  return looksLikeLabelMap(moving) ? Interpolation::Nearest : Interpolation::Linear;
}

Volume resample(const Volume& moving, const Grid& fixedGrid, const Transform& fixedFromMoving,
                const ResampleOptions& options) {
  if (moving.empty()) throw Error("resample: the moving volume is empty");
  const auto dims = fixedGrid.dimensions;
  if (dims.x < 1 || dims.y < 1 || dims.z < 1) throw Error("resample: the output grid is empty");

  const bool asStored = options.allComponents || moving.components() == 1;
  const Volume firstOnly = asStored ? Volume() : firstComponent(moving);
  const Volume& source = asStored ? moving : firstOnly;
  const Interpolation interpolation = chosenInterpolation(source, options);

  // Output index -> input index: movingIndexFromWorld * movingFromFixed * fixedWorldFromIndex.
  const glm::dmat4 movingIndexFromFixedIndex = glm::inverse(moving.worldFromIndex()) *
                                               fixedFromMoving.movingFromFixed() *
                                               fixedGrid.worldFromIndex;
  auto axes = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      axes->SetElement(row, col, movingIndexFromFixedIndex[col][row]);

  auto reslice = vtkSmartPointer<vtkImageReslice>::New();
  // The moving voxels seen by VTK without a copy, on an image with unit spacing and zero
  // origin: all geometry, direction included, goes into the reslice axes, so nothing depends
  // on which VTK filters honour vtkImageData's own direction matrix.
  const vtkSmartPointer<vtkImageData> input = io::imageViewOfVolume(source);
  reslice->SetInputData(input);
  reslice->SetResliceAxes(axes);
  reslice->SetOutputSpacing(1, 1, 1);
  reslice->SetOutputOrigin(0, 0, 0);
  reslice->SetOutputDimensionality(3);
  reslice->SetBackgroundLevel(options.background);
  switch (interpolation) {
    case Interpolation::Nearest:
      reslice->SetInterpolationModeToNearestNeighbor();
      break;
    case Interpolation::Cubic:
      reslice->SetInterpolationModeToCubic();
      break;
    case Interpolation::Linear:
    case Interpolation::Automatic:
      reslice->SetInterpolationModeToLinear();
      break;
  }

  // Slabs of output slices, each copied into place: VTK's output buffer is then a slab, not
  // a second copy of the whole output (which would double the peak memory of mvw register).
  Volume out(dims, source.components(), source.scalarType(), fixedGrid.worldFromIndex);
  const std::size_t sliceBytes = out.byteSize() / static_cast<std::size_t>(dims.z);
  const int slab = static_cast<int>(std::clamp<std::size_t>(
      (4u << 20) / std::max<std::size_t>(sliceBytes, 1), 1, static_cast<std::size_t>(dims.z)));
  for (int z0 = 0; z0 < dims.z; z0 += slab) {
    const int z1 = std::min(dims.z, z0 + slab) - 1;
    reslice->SetOutputExtent(0, dims.x - 1, 0, dims.y - 1, z0, z1);
    reslice->Update();
    vtkDataArray* scalars = reslice->GetOutput()->GetPointData()->GetScalars();
    MVW_CHECK(scalars != nullptr);
    MVW_CHECK_EQ(scalars->GetDataType(), input->GetScalarType());
    MVW_CHECK_EQ(
        static_cast<std::size_t>(scalars->GetNumberOfValues()) * scalarSize(source.scalarType()),
        sliceBytes * static_cast<std::size_t>(z1 - z0 + 1));
    std::memcpy(out.data() + sliceBytes * static_cast<std::size_t>(z0), scalars->GetVoidPointer(0),
                sliceBytes * static_cast<std::size_t>(z1 - z0 + 1));
  }

  out.metadata() = source.metadata();
  out.metadata().format.clear();
  out.metadata().sliceSpacing.reset();
  out.metadata().notes.push_back(std::string("resampled onto a ") + std::to_string(dims.x) + " x " +
                                 std::to_string(dims.y) + " x " + std::to_string(dims.z) +
                                 " grid, " + name(interpolation) + " interpolation");
  return out;
}

}  // namespace mvw::resampling
