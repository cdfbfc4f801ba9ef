#pragma once
// Copies between mvw::Volume and vtkImageData (internal to mvw_io).
#include <filesystem>

#include <vtkSmartPointer.h>

#include "mvw/core/Volume.h"

class vtkImageData;

namespace mvw::io::detail {

// Voxels and dimensions of `image`, with worldFromIndex left as identity for the caller to set.
// Throws InputError naming `file` for scalar types mvw does not handle.
Volume volumeFromImage(vtkImageData* image, const std::filesystem::path& file);

// The other direction is mvw/io/VtkImageView.h (imageViewOfVolume), shared with resampling.

}  // namespace mvw::io::detail
