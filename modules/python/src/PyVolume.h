#pragma once
// mvw.Volume: a core Volume shared with Python (docs/python.md#mvwvolume). Its voxels reach
// NumPy as a view, never a copy: the array's base is the Python Volume, which keeps the C++
// volume alive as long as any view of it.
#include <memory>

#include <pybind11/pybind11.h>

#include "mvw/core/Volume.h"

namespace mvw::python {

using VolumePtr = std::shared_ptr<Volume>;

// Adds mvw.Volume to `m`.
void bindVolume(pybind11::module_& m);

}  // namespace mvw::python
