#pragma once
// mvw.Volume: a core Volume shared with Python (docs/python.md#mvwvolume). Its voxels reach
// NumPy as a view, never a copy: the array's base is the Python Volume, which keeps the C++
// volume alive as long as any view of it.
#include <memory>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <glm/mat4x4.hpp>

#include "mvw/core/Volume.h"

namespace mvw::python {

using VolumePtr = std::shared_ptr<Volume>;

using Matrix = pybind11::array_t<double, pybind11::array::c_style>;

// A volume's 4 x 4 affine (voxel index -> LPS mm) as NumPy rows; with `ras`, its output in RAS
// (the x and y rows negated: NIfTI's and nibabel's world).
Matrix matrixOf(const glm::dmat4& m, bool ras);

// Adds mvw.Volume to `m`.
void bindVolume(pybind11::module_& m);

}  // namespace mvw::python
