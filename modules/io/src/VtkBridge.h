#pragma once
// Copies between mvw::Volume and vtkImageData (internal to mvw_io).
#include <filesystem>

#include <vtkSmartPointer.h>

#include "mvw/core/Volume.h"

class vtkImageData;

namespace mvw::io::detail {

// A volume of `dims`, `components` and the VTK scalar type `vtkType`, its voxels zero, for a
// caller to fill. Throws InputError naming `file` for a type mvw does not handle or no voxels.
Volume volumeOfVtkType(glm::ivec3 dims, int components, int vtkType,
                       const std::filesystem::path& file);

// Voxels and dimensions of `image`, with worldFromIndex left as identity for the caller to set.
// Throws InputError naming `file` for scalar types mvw does not handle.
Volume volumeFromImage(vtkImageData* image, const std::filesystem::path& file);

// The other direction is mvw/io/VtkImageView.h (imageViewOfVolume), shared with resampling.

}  // namespace mvw::io::detail
