// The Python module `mvw` (docs/python.md): mvw.read, mvw.stats, mvw.Volume and the errors.
// Each function checks its Python arguments (what CLI11 does for the command line) and calls the
// module libraries, as the command of the same name does; nothing else.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <nlohmann/json.hpp>

#include "PyErrors.h"
#include "PyPacs.h"
#include "PyRegistration.h"
#include "PyStudy.h"
#include "PyVolume.h"
#include "mvw/core/Error.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/study/RoiReport.h"
#include "mvw/study/VolumeConversion.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

// `frame` as the command line's --frame: a frame number (from 0) or "mean".
std::string frameText(const py::object& frame) {
  if (frame.is_none()) return "";
  if (py::isinstance<py::str>(frame)) return frame.cast<std::string>();
  if (py::isinstance<py::int_>(frame) && !py::isinstance<py::bool_>(frame))
    return std::to_string(frame.cast<long long>());
  throw py::type_error("mvw.read: frame must be a frame number (an int from 0) or 'mean', not " +
                       py::str(py::type::of(frame).attr("__name__")).cast<std::string>());
}

VolumePtr readPath(const std::filesystem::path& path, const std::optional<std::string>& series,
                   const py::object& frame, bool suv, const std::optional<std::string>& volume) {
  // The command line's refusals (mvw convert), said with the arguments' Python names.
  const bool fromStudy = study::isStudyConfig(path);
  if (fromStudy && series)
    throw py::value_error("mvw.read: series chooses a DICOM series of a folder; the study config " +
                          path.string() + " names its series itself");
  if (fromStudy && !frame.is_none())
    throw py::value_error("mvw.read: frame chooses a frame of a volume file; the study config " +
                          path.string() + " chooses with its \"frame\"");
  if (!fromStudy && volume)
    throw py::value_error("mvw.read: volume chooses a volume of a study config (.json); " +
                          path.string() + " is a volume");
  study::ConversionRequest request;
  request.input = path.string();
  request.series = series.value_or("");
  request.frame = frameText(frame);
  request.volume = volume.value_or("");
  request.suv = suv;
  py::gil_scoped_release released;
  return std::make_shared<Volume>(study::readConversionInput(request, pacs::Options{}));
}

// A sequence of `n` finite numbers (the command line's --sphere and --box), or empty for None.
std::vector<double> numbers(const std::optional<std::vector<double>>& given, std::size_t n,
                            const char* name, const char* form) {
  if (!given) return {};
  if (given->size() != n)
    throw py::value_error(std::string("mvw.stats: ") + name + " is " + form + ", " +
                          std::to_string(n) + " numbers, not " + std::to_string(given->size()));
  for (double v : *given)
    if (!std::isfinite(v))
      throw py::value_error(std::string("mvw.stats: ") + name + " must be finite numbers");
  return *given;
}

py::object statsOf(const VolumePtr& volume, const std::optional<std::vector<double>>& sphere,
                   const std::optional<std::vector<double>>& box,
                   const std::optional<std::filesystem::path>& labels, int label,
                   const std::optional<double>& threshold,
                   const std::optional<double>& thresholdFraction) {
  study::RoiOptions roi;
  roi.sphere = numbers(sphere, 4, "sphere", "(x, y, z, radius) in LPS mm");
  roi.box = numbers(box, 6, "box", "(x0, y0, z0, x1, y1, z1) in LPS mm");
  if (labels) roi.labels = labels->string();
  roi.label = label;
  if (threshold) {
    if (!std::isfinite(*threshold))
      throw py::value_error("mvw.stats: threshold must be a finite number");
    roi.threshold = *threshold;
  }
  if (thresholdFraction) roi.thresholdFraction = *thresholdFraction;
  // The command line's checks (mvw stats), said with the arguments' Python names.
  const study::RoiOptionNames names{"sphere", "box", "labels", "threshold", "threshold_fraction",
                                    "label"};
  if (const auto problem = study::roiOptionsProblem(roi, names)) {
    throw py::value_error("mvw.stats: " + (problem->ofOption ? problem->option + " " : "") +
                          problem->problem);
  }
  const int rois = !roi.sphere.empty() + !roi.box.empty() + !roi.labels.empty();
  const std::string kRoiChoice = "mvw.stats: " + study::roiChoice(names);
  // Without an ROI, as mvw stats: the one DICOM SEG beside the series the volume was read from.
  if (rois == 0) {
    const auto found = study::defaultLabels(*volume, {}, {});
    if (!found) throw py::value_error(kRoiChoice);
    roi.labels = found->path;
  }

  const py::object warn = py::module_::import("warnings").attr("warn");
  const std::filesystem::path source = volume->metadata().sourcePath.empty()
                                           ? std::filesystem::path("<mvw.Volume from an array>")
                                           : std::filesystem::path(volume->metadata().sourcePath);
  const study::RoiReport report =
      study::roiReport(*volume, study::roiRequestOf(roi), source,
                       [&warn](const std::string& note) { warn("mvw.stats: note: " + note); });
  const py::object list =
      py::module_::import("json").attr("loads")(study::roiReportJson(report).dump());
  // One ROI asked for (a sphere, a box, one label): its dict; every label: the list.
  const bool one = !roi.sphere.empty() || !roi.box.empty() || roi.label != 0;
  return one ? py::object(list[py::int_(0)]) : list;
}

}  // namespace

}  // namespace mvw::python

PYBIND11_MODULE(mvw, m) {
  using namespace mvw::python;
  m.doc() = R"doc(mvw from Python: read DICOM, NIfTI and MetaImage volumes into NumPy with mvw's
geometry and units, measure them as `mvw stats` does, register them as `mvw register` does,
render a study's views as `mvw render` does, and query a PACS (docs/python.md).

    import mvw
    ct = mvw.read("data/cranium/dicom")         # a DICOM folder, file, NIfTI, MetaImage
    ct.array                                    # NumPy view [i, j, k], in ct.unit (HU)
    ct.affine_ras                               # 4 x 4, voxel index -> RAS mm
    mvw.stats(ct, sphere=(0, 0, 0, 20))         # dict: the fields of `mvw stats --json`
    reg = mvw.register(ct, pet)                 # reg.fixed_from_moving, reg.resample()
    mvw.Study("study.json").render("bone")      # (H, W, 4) uint8: bone.png's pixels
    mvw.pacs.get(server, study, series, read=True)  # a PACS series, as a study reads it

Errors: mvw.InputError (a ValueError naming the file), mvw.ServiceError (a ConnectionError
naming the server), TypeError for an argument of the wrong type.)doc";
  bindErrors(m);
  bindVolume(m);
  bindRegistration(m);
  bindStudy(m);
  bindPacs(m);
  m.def("read", &readPath, py::arg("path"), py::arg("series") = py::none(),
        py::arg("frame") = py::none(), py::arg("suv") = true, py::kw_only(),
        py::arg("volume") = py::none(), R"doc(
Reads one volume: a DICOM folder or file, NIfTI (.nii, .nii.gz, .hdr/.img), MetaImage
(.mha, .mhd), or a study config (.json): its anatomical volume, or the one `volume` names
('functional', 'segmentation'), read as every mvw command reads the study. As `mvw convert`
reads its input.

series: of a DICOM folder that holds several, a SeriesInstanceUID, a SeriesNumber or a part of
    the SeriesDescription (None: the folder must hold one).
frame:  of a 4D volume file, a frame number (from 0) or 'mean' (None: every frame, as the
    array's 4th axis).
suv:    PET values in SUVbw where the DICOM tags allow it (False: Bq/ml).

Returns an mvw.Volume. Raises mvw.InputError (a ValueError) naming the file that cannot be
read, mvw.ServiceError for a study's PACS series that cannot be retrieved, TypeError for an
argument of the wrong type. The interpreter's other threads run while it reads.)doc");
  m.def("stats", &statsOf, py::arg("volume"), py::kw_only(), py::arg("sphere") = py::none(),
        py::arg("box") = py::none(), py::arg("labels") = py::none(), py::arg("label") = 0,
        py::arg("threshold") = py::none(), py::arg("threshold_fraction") = py::none(), R"doc(
Statistics of `volume` in a region of interest, as `mvw stats --json` reports them: voxels,
volume_ml, max, mean, sd, SUVpeak (for a volume in SUV), and the metabolic volume with a
threshold. Exactly one ROI:

sphere: (x, y, z, radius), the centre in LPS mm, the radius in mm.
box:    (x0, y0, z0, x1, y1, z1), opposite corners in LPS mm.
labels: a label map file: a DICOM SEG (one ROI per segment) or a label volume (one per value);
    label: only this label or segment (0: every one).
None of them: the DICOM SEG beside a folder's one image series, as the command line does.
threshold / threshold_fraction: the metabolic volume, voxels at or above this value, or this
    fraction (0 < f <= 1) of the ROI's max.

Returns the dict of the one ROI (a sphere, a box, one label), or for every label the list of
`mvw stats --json`: a dict per ROI, then the total over a SEG's segments. What the command line
says as a note (a label table that cannot be read, a PET left in Bq/ml) is a UserWarning.)doc");
}
