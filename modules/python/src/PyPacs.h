#pragma once
// mvw.pacs.find and mvw.pacs.get (docs/python.md#mvwpacs): `mvw pacs find` and a study's PACS
// series from Python, over the same library functions (pacs::findStudies, findStudySeries, and
// the study loader's study::localPath and readLocal over pacs::cachedSeries).
#include <pybind11/pybind11.h>

namespace mvw::python {

// Adds the submodule mvw.pacs to `m`.
void bindPacs(pybind11::module_& m);

}  // namespace mvw::python
