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

// An image sharing the volume's voxels (no copy; writers only read), with origin 0 and unit
// spacing (geometry is the caller's: each format places it differently). The volume must
// outlive the image.
vtkSmartPointer<vtkImageData> imageViewOfVolume(const Volume& volume);

}  // namespace mvw::io::detail
