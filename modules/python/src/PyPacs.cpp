#include "PyPacs.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "PyVolume.h"
#include "mvw/config/ServerList.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/study/StudyLoader.h"

namespace py = pybind11;

namespace mvw::python {

namespace {

// The command line's connection options (--calling-aet, --connect-timeout, --read-timeout,
// main's --cache), and no progress line: a notebook is no terminal.
pacs::Options optionsOf(const std::string& callingAet, double connectTimeout, double readTimeout,
                        const std::optional<std::filesystem::path>& cache) {
  if (!pacs::isAeTitle(callingAet))
    throw py::value_error("mvw.pacs: calling_aet is 1 to 16 characters, not '" + callingAet + "'");
  if (!(connectTimeout > 0.0) || !(readTimeout > 0.0))
    throw py::value_error("mvw.pacs: connect_timeout and read_timeout are seconds above 0");
  pacs::Options options;
  options.callingAet = callingAet;
  options.connectTimeoutS = connectTimeout;
  options.readTimeoutS = readTimeout;
  options.progress = false;
  if (cache) options.cacheDir = *cache;
  return options;
}

std::vector<pacs::Match> find(const std::string& server, const std::string& patientId,
                              const std::string& patientName, const std::string& studyDate,
                              const std::string& modality, const std::string& accession,
                              const std::optional<std::string>& study,
                              const std::string& callingAet, double connectTimeout,
                              double readTimeout) {
  const pacs::Options options = optionsOf(callingAet, connectTimeout, readTimeout, std::nullopt);
  py::gil_scoped_release released;
  const pacs::Server resolved = config::resolveServer(server);
  if (study) return pacs::findStudySeries(resolved, *study, options);
  pacs::StudyQuery query;
  query.patientId = patientId;
  query.patientName = patientName;
  query.studyDate = studyDate;
  query.modality = modality;
  query.accession = accession;
  return pacs::findStudies(resolved, query, options);
}

// A study config's PACS series ("pacs", "study", "series"): its verified cache folder
// (study::localPath), or with `read` the volume read from it as a study reads it
// (study::readLocal: a cached file that fails to read moves the series into the quarantine).
py::object get(const std::string& server, const std::string& study, const std::string& series,
               const std::optional<std::filesystem::path>& cache, bool read, bool suv,
               const std::string& callingAet, double connectTimeout, double readTimeout) {
  const pacs::Options options = optionsOf(callingAet, connectTimeout, readTimeout, cache);
  config::VolumeSource source;
  source.pacs = server;
  source.study = study;
  source.series = series;
  if (!read) {
    std::filesystem::path folder;
    {
      py::gil_scoped_release released;
      folder = study::localPath(source, options);
    }
    return py::cast(folder);
  }
  io::ReadOptions readOptions;
  readOptions.suv = suv;
  VolumePtr volume;
  {
    py::gil_scoped_release released;
    volume = std::make_shared<Volume>(
        study::readLocal(source, options, [&readOptions](const std::filesystem::path& folder) {
          return io::readVolume(folder, readOptions);
        }));
  }
  return py::cast(volume);
}

}  // namespace

void bindPacs(py::module_& m) {
  const pacs::Options defaults;  // the command line's defaults: one home, pacs::Options
  py::module_ pacs = m.def_submodule("pacs", R"doc(
Query and retrieve from a PACS, as `mvw pacs find` and a study config's PACS series do:
DICOMweb (http(s)://host:port/ROOT) or DIMSE (dicom://AET@host:port), or a server's name saved
in servers.json; credentials from MVW_PACS_USER / MVW_PACS_PASSWORD or MVW_PACS_CREDENTIALS.
A server that cannot be reached, refuses or breaks off raises mvw.ServiceError naming it.)doc");
  pacs.def("find", &find, py::arg("server"), py::kw_only(), py::arg("patient_id") = "",
           py::arg("patient_name") = "", py::arg("study_date") = "", py::arg("modality") = "",
           py::arg("accession") = "", py::arg("study") = py::none(),
           py::arg("calling_aet") = defaults.callingAet,
           py::arg("connect_timeout") = defaults.connectTimeoutS,
           py::arg("read_timeout") = defaults.readTimeoutS, R"doc(
The studies matching the keys, or with study=UID that study's series: a list of dicts keyed by
DICOM keyword (StudyInstanceUID, PatientID, SeriesInstanceUID, Modality, ...), as
`mvw pacs find --json` prints them. patient_name takes the wildcards * and ?; study_date is
YYYYMMDD or YYYYMMDD-YYYYMMDD. A study the server does not have raises mvw.InputError.)doc");
  pacs.def("get", &get, py::arg("server"), py::arg("study"), py::arg("series"),
           py::arg("cache") = py::none(), py::kw_only(), py::arg("read") = false,
           py::arg("suv") = true, py::arg("calling_aet") = defaults.callingAet,
           py::arg("connect_timeout") = defaults.connectTimeoutS,
           py::arg("read_timeout") = defaults.readTimeoutS, R"doc(
The series `series` (its UID, number, modality or part of its description) of study `study`,
from the verified cache, retrieved first unless it is there complete and verified: as a study
config's PACS series ("pacs", "study", "series") is read.

Returns the cache folder that holds the series, a pathlib.Path (mvw.read(path) reads it), or
with read=True the series read into an mvw.Volume (suv as mvw.read's). With read=True a cached
file that fails to read moves the series into the cache's quarantine, so the next call
retrieves it again; the mvw.InputError names the file where it now lies.

cache: the cache folder (None: $XDG_CACHE_HOME/mvw/dicom or ~/.cache/mvw/dicom, as the command
line's --cache). The interpreter's other threads run while it retrieves and reads.)doc");
}

}  // namespace mvw::python
