#pragma once
// mvw's error types as Python exceptions (docs/python.md#errors): the errors the command line
// turns into exit 2 (mvw::InputError, a path the file system refused) raise mvw.InputError, a
// ValueError naming the file; those it turns into exit 3 (mvw::ServiceError) raise
// mvw.ServiceError, a ConnectionError naming the server. Anything else keeps pybind11's
// mapping (RuntimeError, MemoryError): an internal fault never aborts the interpreter.
#include <pybind11/pybind11.h>

namespace mvw::python {

// Adds mvw.InputError and mvw.ServiceError to `m` and translates the C++ errors into them.
void bindErrors(pybind11::module_& m);

}  // namespace mvw::python
