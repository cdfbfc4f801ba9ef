#pragma once
// Copies between mvw::Volume and vtkImageData (internal to mvw_io).
#include <filesystem>

#include <vtkSmartPointer.h>

#include "mvw/core/Volume.h"

class vtkImageData;
class vtkInformation;

namespace mvw::io::detail {

// What a reader's output information (after UpdateInformation) says its voxels are: the
// dimensions of its whole extent, the components (at least 1) and the VTK scalar type.
struct VoxelLayout {
  glm::ivec3 dims;
  int components;
  int vtkType;
};
VoxelLayout voxelLayout(vtkInformation* info);

// A volume of `dims`, `components` and the VTK scalar type `vtkType`, its voxels zero, for a
// caller to fill. Throws InputError naming `file` for a type mvw does not handle or no voxels.
Volume volumeOfVtkType(glm::ivec3 dims, int components, int vtkType,
                       const std::filesystem::path& file);

// Voxels and dimensions of `image`, with worldFromIndex left as identity for the caller to set.
// Throws InputError naming `file` for scalar types mvw does not handle.
Volume volumeFromImage(vtkImageData* image, const std::filesystem::path& file);

// The other direction is mvw/io/VtkImageView.h (imageViewOfVolume), shared with resampling.

}  // namespace mvw::io::detail
