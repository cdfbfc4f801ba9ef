#include "PyErrors.h"

#include <exception>
#include <filesystem>
#include <string>

#include "mvw/core/Error.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

// The exception classes live as long as the interpreter: held without a reference count of
// ours, so nothing is released after the interpreter has finalised.
PyObject* inputErrorType = nullptr;
PyObject* serviceErrorType = nullptr;

// Raises `type(message)` with the attributes given (the file of an InputError).
void raise(PyObject* type, const std::string& message, const std::string& file = {},
           const std::string& problem = {}) {
  py::object error = py::reinterpret_borrow<py::object>(type)(message);
  error.attr("file") = file.empty() ? py::object(py::none()) : py::object(py::str(file));
  if (!problem.empty()) error.attr("problem") = problem;
  PyErr_SetObject(type, error.ptr());
}

}  // namespace

void bindErrors(py::module_& m) {
  const py::object input = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("mvw.InputError",
                                "A file, folder or study config that cannot be used (the command "
                                "line's exit 2). str() names the file and the problem; .file is "
                                "the file (a str), .problem what is wrong with it.",
                                PyExc_ValueError, nullptr));
  const py::object service = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "mvw.ServiceError",
      "A server (a PACS) that could not be reached, refused, timed out or broke off (the "
      "command line's exit 3). str() names the server and what it said.",
      PyExc_ConnectionError, nullptr));
  m.add_object("InputError", input);
  m.add_object("ServiceError", service);
  inputErrorType = input.ptr();
  serviceErrorType = service.ptr();
  Py_INCREF(inputErrorType);
  Py_INCREF(serviceErrorType);

  // The same classes as mvw::exitCodeOf, in its order.
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      std::rethrow_exception(error);
    } catch (const ServiceError& e) {
      raise(serviceErrorType, e.what());
    } catch (const InputError& e) {
      raise(inputErrorType, e.what(), e.file().string(), e.problem());
    } catch (const std::filesystem::filesystem_error& e) {
      raise(inputErrorType, e.path1().string() + ": " + e.code().message(), e.path1().string(),
            e.code().message());
    }
  });
}

}  // namespace mvw::python
