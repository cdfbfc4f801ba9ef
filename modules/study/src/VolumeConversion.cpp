#include "mvw/study/VolumeConversion.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/StagedFolder.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/study/VolumeReport.h"

namespace mvw::study {

namespace fs = std::filesystem;

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string volumeName(const ConversionRequest& request) {
  return request.volume.empty() ? "anatomical" : request.volume;
}

}  // namespace

fs::path sidecarOf(const fs::path& output) {
  const std::string name = output.filename().string();
  for (const char* ext : {".nii.gz", ".nii", ".mha"})
    if (endsWith(name, ext) && name.size() > std::string(ext).size())
      return output.parent_path() /
             (name.substr(0, name.size() - std::string(ext).size()) + ".json");
  return {};
}

fs::path checkConversionOutput(const ConversionRequest& request) {
  const fs::path& output = request.output;
  const fs::path sidecar = sidecarOf(output);
  if (sidecar.empty())
    throw InputError(output, "unknown output format (use .nii.gz, .nii or .mha)");
  io::checkVolumeOutput(output, {request.input});
  std::error_code ec;
  if (fs::equivalent(sidecar, request.input, ec))
    throw InputError(sidecar, "the sidecar's name is the input's: choose another output name");
  if (fs::is_directory(sidecar, ec))
    throw InputError(sidecar, "the sidecar's name is taken by a folder");
  // OUT.json is replaced only when an earlier `mvw convert` wrote it.
  if (fs::exists(sidecar, ec)) {
    std::ifstream in(sidecar);
    const nlohmann::json old = nlohmann::json::parse(in, nullptr, false);
    const bool ours = old.is_object() && old.contains("written_by") &&
                      old["written_by"].is_string() && old["written_by"] == "mvw convert";
    if (!ours)
      throw InputError(sidecar,
                       "the sidecar's name is taken by a file mvw convert did not write; move it "
                       "or choose another output name");
  }
  return sidecar;
}

Volume readStudyVolume(const std::string& studyPath, const std::string& which,
                       const io::ReadOptions& read, const pacs::Options& pacs) {
  const config::StudyConfig study = config::loadStudyConfig(studyPath);
  if (which.empty() || which == "anatomical") return readAnatomical(study.anatomical, read, pacs);
  if (which == "functional") {
    if (!study.functional)
      throw InputError(studyPath, "the study names no functional volume (--volume functional)");
    return readFunctional(study, read, pacs);
  }
  if (!study.segmentation)
    throw InputError(studyPath, "the study names no segmentation (--volume segmentation)");
  if (study.segmentation->frame && study.segmentation->frame->mean)
    throw InputError(studyPath,
                     "'segmentation.frame' cannot be \"mean\": label numbers are not averaged");
  return readSource(*study.segmentation, read, pacs);  // a DICOM SEG: its label volume
}

Volume readConversionInput(const ConversionRequest& request, const pacs::Options& pacs) {
  std::optional<FrameChoice> frame;
  if (!request.frame.empty()) {
    frame = parseFrameChoice(request.frame);
    if (!frame)
      throw InputError(request.input, "--frame '" + request.frame +
                                          "' must be a frame number (0, 1, ...) or 'mean'");
  }
  io::ReadOptions read;
  read.series = request.series;
  read.suv = request.suv;
  Volume volume = isStudyConfig(request.input)
                      ? readStudyVolume(request.input, request.volume, read, pacs)
                      : io::readVolume(request.input, read);
  if (frame) volume = selectFrame(volume, *frame);
  return volume;
}

nlohmann::json conversionSidecar(nlohmann::json description, const Volume& volume,
                                 const ConversionRequest& request) {
  nlohmann::json j = std::move(description);
  j.erase("path");
  j["source_path"] = fs::absolute(request.input).lexically_normal().string();
  const auto& md = volume.metadata();
  j["series_description"] = md.seriesDescription;
  j["series_number"] = seriesNumberJson(md.seriesNumber);
  j["series_instance_uid"] = md.seriesInstanceUid;
  if (md.suvFactor) j["suv_factor"] = *md.suvFactor;  // SUVbw = Bq/ml x suv_factor
  if (isStudyConfig(request.input)) {
    j["study_volume"] = volumeName(request);
    j["frame"] = "as the study config reads it";
  } else {
    j["frame"] = request.frame.empty() ? nlohmann::json("all") : nlohmann::json(request.frame);
  }
  j["written_by"] = "mvw convert";
  return j;
}

void writeConversion(const Volume& volume, const fs::path& output, const fs::path& sidecar,
                     const std::string& sidecarText) {
  try {
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    io::StagedFolder staging(folder,
                             {.purpose = "convert", .place = io::StagedFolder::Place::Inside});
    io::writeVolume(volume, staging.path() / output.filename());
    io::writeTextAtomically(staging.path() / sidecar.filename(), sidecarText);
    staging.commit({output.filename().string(), sidecar.filename().string()});
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // The output is a name the user typed: a place that cannot be written is bad input.
    throw InputError(output, std::string("cannot be written: ") + e.what());
  }
}

std::string conversionSummary(const Volume& volume, const ConversionRequest& request,
                              const fs::path& sidecar) {
  const glm::ivec3 d = volume.dimensions();
  std::ostringstream out;
  out << "wrote " << request.output.string() << " (" << d.x << " x " << d.y << " x " << d.z;
  if (volume.components() > 1) out << " x " << volume.components() << " frames";
  out << ", " << scalarName(volume.scalarType())
      << (volume.metadata().unit.empty() ? "" : ", " + volume.metadata().unit) << ") and "
      << sidecar.string();
  if (isStudyConfig(request.input))
    out << ": the " << volumeName(request) << " volume of " << request.input
        << (request.volume.empty() ? " (--volume functional|segmentation for the others)" : "");
  out << "\n";
  return out.str();
}

}  // namespace mvw::study
