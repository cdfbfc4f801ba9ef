#pragma once
// mvw.register and mvw.Registration (docs/python.md#mvwregister): `mvw register` from Python,
// over the same library functions (resampling::registerRigid, output::registrationJson).
#include <pybind11/pybind11.h>

namespace mvw::python {

// Adds mvw.register and mvw.Registration to `m`.
void bindRegistration(pybind11::module_& m);

}  // namespace mvw::python
