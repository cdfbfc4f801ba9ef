#pragma once
// A zero-copy vtkImageData view of a Volume's voxels (unit spacing, zero origin: geometry is
// the caller's), for the .cpp files of io and resampling that hand voxels to VTK filters
// which only read them. The volume must outlive the image. Include it only from .cpp files:
// it brings vtkSmartPointer.h.
#include <vtkSmartPointer.h>

#include "mvw/core/Volume.h"

class vtkImageData;

namespace mvw::io {

vtkSmartPointer<vtkImageData> imageViewOfVolume(const Volume& volume);

}  // namespace mvw::io
