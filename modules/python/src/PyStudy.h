#pragma once
// mvw.Study and its render (docs/python.md#mvwstudy): `mvw render` of one view, from Python, over
// the same library functions (study::Session, output::viewPainter), on the module's GL thread.
#include <pybind11/pybind11.h>

namespace mvw::python {

// Adds mvw.Study and mvw.read_png to `m`.
void bindStudy(pybind11::module_& m);

}  // namespace mvw::python
