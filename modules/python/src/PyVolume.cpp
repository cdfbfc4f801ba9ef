#include "PyVolume.h"

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "mvw/core/ScalarType.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

// LPS -> RAS: x and y change sign (nibabel's and NIfTI's world is RAS).
constexpr std::array<double, 4> kLpsToRas{-1.0, -1.0, 1.0, 1.0};

}  // namespace

Matrix matrixOf(const glm::dmat4& m, bool ras) {
  Matrix out({4, 4});
  auto r = out.mutable_unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      r(row, col) = m[col][row] * (ras ? kLpsToRas[static_cast<std::size_t>(row)] : 1.0) +
                    0.0;  // + 0.0: no -0 where a zero changed sign
  return out;
}

namespace {

glm::dmat4 glmOf(const py::handle& affine, bool ras, const char* name) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(affine);
  if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw py::type_error(std::string(name) + " must be a 4 x 4 array of numbers");
  const auto r = a.unchecked<2>();
  glm::dmat4 m(1.0);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      m[col][row] = r(row, col) * (ras ? kLpsToRas[static_cast<std::size_t>(row)] : 1.0);
  return m;
}

py::dtype dtypeOf(ScalarType type) {
  return dispatchScalar(type, [](auto t) { return py::dtype::of<decltype(t)>(); });
}

std::optional<ScalarType> scalarTypeOfDtype(const py::dtype& d) {
  for (ScalarType t :
       {ScalarType::UInt8, ScalarType::Int8, ScalarType::UInt16, ScalarType::Int16,
        ScalarType::UInt32, ScalarType::Int32, ScalarType::Float32, ScalarType::Float64})
    if (dtypeOf(t).equal(d)) return t;  // native byte order only: '>i2' is not int16 here
  return std::nullopt;
}

// The voxels as an array indexed [i, j, k] (and [i, j, k, c] with components), i fastest in
// memory: nibabel's order, and the order the affines multiply (i, j, k, 1). A view: `owner`
// (the Python Volume) is its base.
py::array arrayOf(const VolumePtr& volume, py::handle owner) {
  const glm::ivec3 d = volume->dimensions();
  const auto size = static_cast<py::ssize_t>(scalarSize(volume->scalarType()));
  const auto c = static_cast<py::ssize_t>(volume->components());
  std::vector<py::ssize_t> shape{d.x, d.y, d.z};
  std::vector<py::ssize_t> strides{size * c, size * c * d.x, size * c * d.x * d.y};
  if (c > 1) {
    shape.push_back(c);
    strides.push_back(size);
  }
  return py::array(dtypeOf(volume->scalarType()), shape, strides, volume->data(), owner);
}

VolumePtr fromArray(const py::array& array, const py::object& affineLps,
                    const py::object& affineRas, const std::string& modality,
                    const std::string& unit) {
  const auto type = scalarTypeOfDtype(array.dtype());
  if (!type)
    throw py::type_error("mvw.Volume.from_array: the array's dtype " +
                         py::str(array.dtype()).cast<std::string>() +
                         " is not one of uint8, int8, uint16, int16, uint32, int32, float32, "
                         "float64");
  if (array.ndim() != 3 && array.ndim() != 4)
    throw py::value_error(
        "mvw.Volume.from_array: the array must have 3 dimensions [i, j, k] or "
        "4 [i, j, k, component], not " +
        std::to_string(array.ndim()));
  if (affineLps.is_none() == affineRas.is_none())
    throw py::type_error("mvw.Volume.from_array: give exactly one of affine_lps and affine_ras");
  const glm::dmat4 worldFromIndex = affineLps.is_none() ? glmOf(affineRas, true, "affine_ras")
                                                        : glmOf(affineLps, false, "affine_lps");
  // A Volume holds at least one voxel and int-sized axes (its constructor checks, and a failed
  // check aborts): said here as the argument's error.
  for (py::ssize_t axis = 0; axis < array.ndim(); ++axis)
    if (array.shape(axis) < 1 || array.shape(axis) > std::numeric_limits<int>::max())
      throw py::value_error("mvw.Volume.from_array: axis " + std::to_string(axis) +
                            " of the array has " + std::to_string(array.shape(axis)) +
                            " elements; each must have 1 to " +
                            std::to_string(std::numeric_limits<int>::max()));
  const glm::ivec3 dims(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
                        static_cast<int>(array.shape(2)));
  const int components = array.ndim() == 4 ? static_cast<int>(array.shape(3)) : 1;
  auto volume = std::make_shared<Volume>(dims, components, *type, worldFromIndex);
  volume->metadata().modality = modality;
  volume->metadata().unit = unit;
  // Copied in the volume's order (i fastest, components interleaved), whatever the array's.
  py::object owner = py::cast(volume);
  py::array target = arrayOf(volume, owner);
  py::module_::import("numpy").attr("copyto")(target, array);
  return volume;
}

}  // namespace

void bindVolume(py::module_& m) {
  py::class_<Volume, VolumePtr> cls(m, "Volume", R"doc(
A volume: voxels in their physical unit and the geometry that puts them in the patient's world
(LPS millimetres, as DICOM). Made by mvw.read() or Volume.from_array().

Axis order: array[i, j, k] (and array[i, j, k, c] for a 4D volume's frames or a colour
volume's channels), i the fastest in memory: nibabel's order. The affines map a voxel index
(i, j, k, 1) to its centre in millimetres: affine_lps @ (i, j, k, 1) in DICOM's LPS,
affine_ras @ (i, j, k, 1) in NIfTI's RAS (x and y negated).)doc");
  cls.def_property_readonly(
      "array", [](py::object self) { return arrayOf(self.cast<VolumePtr>(), self); },
      "The voxels as a NumPy array [i, j, k] (or [i, j, k, component]), in the physical unit "
      "(.unit). A view, not a copy: writing to it changes the volume, and it keeps the volume "
      "alive.");
  cls.def_property_readonly(
      "affine_lps", [](const Volume& v) { return matrixOf(v.worldFromIndex(), false); },
      "4 x 4 float64: voxel index (i, j, k, 1) -> LPS millimetres (DICOM's world).");
  cls.def_property_readonly(
      "affine_ras", [](const Volume& v) { return matrixOf(v.worldFromIndex(), true); },
      "4 x 4 float64: voxel index (i, j, k, 1) -> RAS millimetres (NIfTI's and nibabel's "
      "world).");
  cls.def_property_readonly(
      "shape",
      [](const Volume& v) {
        const glm::ivec3 d = v.dimensions();
        return v.components() > 1 ? py::make_tuple(d.x, d.y, d.z, v.components())
                                  : py::make_tuple(d.x, d.y, d.z);
      },
      "The array's shape: (ni, nj, nk) or (ni, nj, nk, components).");
  cls.def_property_readonly(
      "spacing",
      [](const Volume& v) {
        const glm::dvec3 s = v.spacing();
        return py::make_tuple(s.x, s.y, s.z);
      },
      "Millimetres between voxel centres along i, j, k.");
  cls.def_property_readonly(
      "dtype", [](const Volume& v) { return dtypeOf(v.scalarType()); },
      "The NumPy dtype of the voxels.");
  cls.def_property_readonly(
      "modality", [](const Volume& v) { return v.metadata().modality; },
      "The DICOM modality code: CT, MR, PT, NM, ... ('' where the file does not say).");
  cls.def_property_readonly(
      "unit", [](const Volume& v) { return v.metadata().unit; },
      "The physical unit of the values: HU, Bq/ml, SUVbw, ... ('' where there is none).");
  cls.def_property_readonly(
      "suv",
      [](const Volume& v) -> py::object {
        if (!v.metadata().suvFactor) return py::none();
        return py::dict(py::arg("factor") = *v.metadata().suvFactor,
                        py::arg("unit") = v.metadata().unit);
      },
      "For a PET read as SUVbw: {'factor': f, 'unit': 'SUVbw'} with SUVbw = Bq/ml x f; "
      "None otherwise.");
  cls.def_property_readonly(
      "notes", [](const Volume& v) { return v.metadata().notes; },
      "What the readers said a user should know (unit decisions, reorderings, resampling), as "
      "a list of str.");
  cls.def_property_readonly(
      "format", [](const Volume& v) { return v.metadata().format; },
      "The file format read: DICOM, NIfTI-1, NIfTI-2, MetaImage ('' for from_array).");
  cls.def_property_readonly(
      "path", [](const Volume& v) { return v.metadata().sourcePath; },
      "The file or folder the volume was read from ('' for from_array).");
  cls.def_property_readonly(
      "series_description", [](const Volume& v) { return v.metadata().seriesDescription; },
      "The DICOM SeriesDescription ('' where there is none).");
  cls.def_property_readonly(
      "series_uid", [](const Volume& v) { return v.metadata().seriesInstanceUid; },
      "The DICOM SeriesInstanceUID ('' for other formats).");
  cls.def_static("from_array", &fromArray, py::arg("array"), py::arg("affine_lps") = py::none(),
                 py::arg("affine_ras") = py::none(), py::kw_only(), py::arg("modality") = "",
                 py::arg("unit") = "", R"doc(
A new volume holding a copy of `array` ([i, j, k] or [i, j, k, component]; uint8, int8,
uint16, int16, uint32, int32, float32 or float64), placed by exactly one of affine_lps and
affine_ras (4 x 4, voxel index -> millimetres). modality and unit say what the values are.
A dtype mvw does not hold, or no affine or two, raise TypeError.)doc");
  cls.def(
      "to_nibabel",
      [](py::object self) {
        py::module_ nibabel;
        try {
          nibabel = py::module_::import("nibabel");
        } catch (py::error_already_set& e) {
          if (!e.matches(PyExc_ImportError)) throw;
          throw py::import_error("mvw.Volume.to_nibabel needs nibabel (Debian: python3-nibabel)");
        }
        return nibabel.attr("Nifti1Image")(self.attr("array"), self.attr("affine_ras"));
      },
      "A nibabel.Nifti1Image of the same voxels (a view) and affine_ras. Raises ImportError "
      "where nibabel is not installed.");
  cls.def("__repr__", [](const Volume& v) {
    const glm::ivec3 d = v.dimensions();
    const glm::dvec3 s = v.spacing();
    std::string text = "<mvw.Volume " + std::to_string(d.x) + " x " + std::to_string(d.y) + " x " +
                       std::to_string(d.z);
    if (v.components() > 1) text += " x " + std::to_string(v.components());
    text += " " + std::string(scalarName(v.scalarType()));
    if (!v.metadata().modality.empty()) text += " " + v.metadata().modality;
    if (!v.metadata().unit.empty()) text += " in " + v.metadata().unit;
    text += ", spacing " + py::str(py::make_tuple(s.x, s.y, s.z)).cast<std::string>() + " mm";
    if (!v.metadata().sourcePath.empty()) text += ", from " + v.metadata().sourcePath;
    return text + ">";
  });
}

}  // namespace mvw::python
