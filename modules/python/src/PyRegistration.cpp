#include "PyRegistration.h"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <nlohmann/json.hpp>

#include "PyVolume.h"
#include "mvw/core/Format.h"
#include "mvw/output/RegistrationRun.h"
#include "mvw/resampling/Resample.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

// A registration's result and what resample() needs: the fixed grid and the moving volume
// (shared with Python: the moving Volume stays alive while its Registration does).
struct Registration {
  resampling::RegistrationResult result;
  resampling::Grid fixedGrid;
  VolumePtr moving;
  resampling::Interpolation interpolation = resampling::Interpolation::Automatic;
  nlohmann::json report;
};

// A volume argument: an mvw.Volume as it is, else a path read as mvw.read reads it.
VolumePtr volumeArg(const py::object& given, bool suv, const char* name) {
  if (py::isinstance<Volume>(given)) return given.cast<VolumePtr>();
  if (!py::isinstance<py::str>(given) &&
      !py::isinstance(given, py::module_::import("os").attr("PathLike")))
    throw py::type_error(std::string("mvw.register: ") + name +
                         " must be an mvw.Volume or a path (str or os.PathLike), not " +
                         py::str(py::type::of(given).attr("__name__")).cast<std::string>());
  return py::module_::import("mvw").attr("read")(given, py::arg("suv") = suv).cast<VolumePtr>();
}

std::string nameOf(const Volume& v) {
  return v.metadata().sourcePath.empty() ? "<mvw.Volume from an array>" : v.metadata().sourcePath;
}

resampling::Interpolation interpolationArg(const std::string& name) {
  const auto parsed = output::parseInterpolation(name);
  if (!parsed)
    throw py::value_error("mvw.register: interpolation is one of " +
                          mvw::joined(output::interpolationNames(), ", ") + ", not '" + name + "'");
  return *parsed;
}

std::shared_ptr<Registration> registerVolumes(const py::object& fixedArg,
                                              const py::object& movingArg,
                                              const std::string& method,
                                              const std::string& initialisation,
                                              double rotationSearch, std::uint64_t seed,
                                              const std::string& interpolation, bool suv) {
  if (method != "rigid" && method != "affine")
    throw py::value_error(
        "mvw.register: method is 'rigid' or 'affine' (rigid, then affine), not '" + method + "'");
  const auto init = output::parseInitialisation(initialisation);
  if (!init)
    throw py::value_error("mvw.register: initialisation is one of " +
                          mvw::joined(output::initialisationNames(), ", ") + ", not '" +
                          initialisation + "'");
  if (!(rotationSearch >= 0.0 && rotationSearch <= 180.0))
    throw py::value_error("mvw.register: rotation_search is 0 to 180 degrees");
  auto reg = std::make_shared<Registration>();
  reg->interpolation = interpolationArg(interpolation);
  const VolumePtr fixed = volumeArg(fixedArg, suv, "fixed");
  reg->moving = volumeArg(movingArg, suv, "moving");
  // As `mvw register` sets them (app/RegisterCommand.cpp): the library's defaults, then these.
  resampling::RegistrationOptions options;
  options.seed = seed;
  options.initialisation = *init;
  options.affine = method == "affine";
  options.rotationSearchRangeDeg = rotationSearch;
  {
    py::gil_scoped_release released;
    reg->result = resampling::registerRigid(*fixed, *reg->moving, options);
    reg->fixedGrid = resampling::gridOf(*fixed);
  }
  output::RegistrationRecord record;
  record.fixedName = nameOf(*fixed);
  record.movingName = nameOf(*reg->moving);
  record.rotationSearchRangeDeg = rotationSearch;
  record.seed = seed;
  resampling::ResampleOptions resampleOptions;
  resampleOptions.interpolation = reg->interpolation;
  record.interpolation = resampling::chosenInterpolation(*reg->moving, resampleOptions);
  record.warnings = output::registrationWarnings(reg->result);
  reg->report = output::registrationJson(reg->result, record);
  // What the command line says as a warning (a final mutual information near 0).
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (const std::string& w : record.warnings) warn("mvw.register: " + w);
  return reg;
}

// The same map in RAS: x and y negated on both sides.
glm::dmat4 rasOf(const glm::dmat4& lps) {
  glm::dmat4 flip(1.0);
  flip[0][0] = flip[1][1] = -1.0;
  return flip * lps * flip;
}

}  // namespace

void bindRegistration(py::module_& m) {
  py::class_<Registration, std::shared_ptr<Registration>> cls(m, "Registration", R"doc(
The result of mvw.register(): the transform that brings the moving volume onto the fixed one,
its report, and the moving volume resampled onto the fixed grid on demand.

The transforms map points (x, y, z, 1) in millimetres, never voxel indices:
  fixed_from_moving:  a point of the moving volume's world -> the same anatomy in the fixed
                      volume's world (what a viewer applies to place the moving volume);
  moving_from_fixed:  its inverse: for each fixed point, where to read the moving volume (what
                      resampling uses, and what an ITK .tfm file holds).
Both in LPS (DICOM's and mvw's world); the *_ras ones are the same maps in RAS (NIfTI's and
nibabel's world: x and y negated on both sides).)doc");
  cls.def_property_readonly(
      "fixed_from_moving",
      [](const Registration& r) { return matrixOf(r.result.transform.fixedFromMoving(), false); },
      "4 x 4 float64, LPS mm: a moving-world point -> the fixed world.");
  cls.def_property_readonly(
      "moving_from_fixed",
      [](const Registration& r) { return matrixOf(r.result.transform.movingFromFixed(), false); },
      "4 x 4 float64, LPS mm: a fixed-world point -> the moving world (the .tfm file's map).");
  cls.def_property_readonly(
      "fixed_from_moving_ras",
      [](const Registration& r) {
        return matrixOf(rasOf(r.result.transform.fixedFromMoving()), false);
      },
      "fixed_from_moving in RAS mm.");
  cls.def_property_readonly(
      "moving_from_fixed_ras",
      [](const Registration& r) {
        return matrixOf(rasOf(r.result.transform.movingFromFixed()), false);
      },
      "moving_from_fixed in RAS mm.");
  cls.def_property_readonly(
      "report",
      [](const Registration& r) {
        return py::module_::import("json").attr("loads")(r.report.dump());
      },
      "The report as a dict: the fields of `mvw register`'s registration.json (method, "
      "levels, parameters, fixed_from_moving, moving_from_fixed, warnings, ...); its "
      "'outputs' is empty (nothing is written).");
  cls.def(
      "resample",
      [](const Registration& r, const std::optional<std::string>& interpolation) {
        resampling::ResampleOptions options;
        options.interpolation = interpolation ? interpolationArg(*interpolation) : r.interpolation;
        py::gil_scoped_release released;
        return std::make_shared<Volume>(
            resampling::resample(*r.moving, r.fixedGrid, r.result.transform, options));
      },
      py::arg("interpolation") = py::none(), R"doc(
The moving volume resampled onto the fixed volume's grid: a new mvw.Volume with the fixed
volume's shape and affines, as `mvw register` writes functional_on_anatomical.nii.gz.
interpolation: auto (nearest for a label map, else linear), linear, nearest or cubic; None:
the one given to mvw.register.)doc");
  cls.def(
      "write_tfm",
      [](const Registration& r, const std::filesystem::path& path) {
        r.result.transform.writeItk(path);
      },
      py::arg("path"), R"doc(
Writes the transform as an ITK text transform (AffineTransform_double_3_3, moving_from_fixed
in LPS), as `mvw register`'s transform.tfm: what a study config's registration "file" method,
SimpleITK, elastix and 3D Slicer read. Written to a temporary name and renamed.)doc");
  cls.def("__repr__", [](const Registration& r) {
    return std::string("<mvw.Registration ") + (r.result.affine ? "rigid then affine" : "rigid") +
           ", " + std::to_string(r.result.iterations) + " iterations" +
           (r.result.converged ? "" : " (not converged)") + ">";
  });

  m.def("register", &registerVolumes, py::arg("fixed"), py::arg("moving"),
        py::arg("method") = "rigid", py::kw_only(), py::arg("initialisation") = "auto",
        py::arg("rotation_search") = 0.0, py::arg("seed") = resampling::RegistrationOptions{}.seed,
        py::arg("interpolation") = "auto", py::arg("suv") = true, R"doc(
Registers `moving` (a functional volume) to `fixed` (the anatomy), as `mvw register --fixed
FIXED --moving MOVING` does: Mattes mutual information, multi-resolution, rigid, or with
method='affine' rigid then affine (12 degrees of freedom).

fixed, moving:   mvw.Volume, or paths read as mvw.read(path, suv=suv) reads them.
initialisation:  auto, world (the headers as they are), centre (bounding boxes), mass
                 (centroids): --init.
rotation_search: score rotations up to this many degrees about each axis first (0: off; for
                 large misalignment): --rotation-search.
seed:            of the sample points (same seed, same result): --seed.
interpolation:   what resample() uses by default: auto, linear, nearest, cubic.

Returns an mvw.Registration. The interpreter's other threads run while it registers. A final
mutual information near 0 (the volumes share no structure) is a UserWarning, as the command
line warns.)doc");
}

}  // namespace mvw::python
