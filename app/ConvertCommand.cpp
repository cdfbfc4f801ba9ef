#include "ConvertCommand.h"

#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Frame.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/StagedFolder.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/study/VolumeReport.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct ConvertOptions {
  std::string input;
  std::string output;
  std::string series;
  std::string frame;  // "": every frame of a 4D volume is written
  bool noSuv = false;
  // Of a study config (.json): which of its volumes; "" is the anatomical one.
  std::string volume;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

bool isStudyConfig(const fs::path& p) { return p.extension() == ".json"; }

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// OUT.nii.gz -> OUT.json (dcm2niix's sidecar name); empty for an extension mvw does not write.
fs::path sidecarOf(const fs::path& output) {
  const std::string name = output.filename().string();
  for (const char* ext : {".nii.gz", ".nii", ".mha"})
    if (endsWith(name, ext) && name.size() > std::string(ext).size())
      return output.parent_path() /
             (name.substr(0, name.size() - std::string(ext).size()) + ".json");
  return {};
}

// Everything about the output that can be wrong is said before the input is read.
void checkOutput(const fs::path& output, const fs::path& sidecar, const fs::path& input) {
  if (sidecar.empty())
    throw InputError(output, "unknown output format (use .nii.gz, .nii or .mha)");
  io::checkVolumeOutput(output, {input});
  std::error_code ec;
  if (fs::equivalent(sidecar, input, ec))
    throw InputError(sidecar, "the sidecar's name is the input's: choose another output name");
  if (fs::is_directory(sidecar, ec))
    throw InputError(sidecar, "the sidecar's name is taken by a folder");
  // OUT.json is replaced only when an earlier `mvw convert` wrote it: the name is also what a
  // study config or another tool's file is called.
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
}

// What dcm2niix's BIDS sidecar says, in mvw's words: what the values are and where they came
// from; the geometry is the image's own (and repeated here for a reader without NIfTI).
nlohmann::json sidecarJson(const Volume& volume, const ConvertOptions& o) {
  nlohmann::json j = study::volumeJson(volume);
  j.erase("path");
  j["source_path"] = fs::absolute(o.input).lexically_normal().string();
  const auto& md = volume.metadata();
  j["series_description"] = md.seriesDescription;
  j["series_number"] = md.seriesNumber;
  j["series_instance_uid"] = md.seriesInstanceUid;
  if (md.suvFactor) j["suv_factor"] = *md.suvFactor;  // SUVbw = Bq/ml x suv_factor
  if (isStudyConfig(o.input)) {
    j["study_volume"] = o.volume.empty() ? "anatomical" : o.volume;
    j["frame"] = "as the study config reads it";
  } else {
    j["frame"] = o.frame.empty() ? nlohmann::json("all") : nlohmann::json(o.frame);
  }
  j["written_by"] = "mvw convert";
  return j;
}

// One volume of a study config, read as every command reads the study (its own series choice,
// "frame" and PACS series from the verified cache): the anatomical one by default.
Volume readStudyVolume(const ConvertOptions& o, const io::ReadOptions& read) {
  const config::StudyConfig study = config::loadStudyConfig(o.input);
  const std::string which = o.volume.empty() ? "anatomical" : o.volume;
  if (which == "anatomical") return study::readAnatomical(study.anatomical, read, o.pacs);
  if (which == "functional") {
    if (!study.functional)
      throw InputError(o.input, "the study names no functional volume (--volume functional)");
    return study::readFunctional(study, read, o.pacs);
  }
  if (!study.segmentation)
    throw InputError(o.input, "the study names no segmentation (--volume segmentation)");
  if (study.segmentation->frame && study.segmentation->frame->mean)
    throw InputError(o.input,
                     "'segmentation.frame' cannot be \"mean\": label numbers are not averaged");
  return study::readSource(*study.segmentation, read, o.pacs);  // a DICOM SEG: its label volume
}

void runConvert(const ConvertOptions& o) {
  const fs::path output = o.output, sidecar = sidecarOf(output);
  const bool fromStudy = isStudyConfig(o.input);
  if (fromStudy && !o.series.empty())
    throw CLI::ValidationError("--series", "chooses a DICOM series of a folder; the study config " +
                                               o.input + " names its series itself");
  if (fromStudy && !o.frame.empty())
    throw CLI::ValidationError("--frame", "chooses a frame of a volume file; the study config " +
                                              o.input + " chooses with its \"frame\"");
  if (!fromStudy && !o.volume.empty())
    throw CLI::ValidationError(
        "--volume", "chooses a volume of a study config (.json); " + o.input + " is a volume");
  checkOutput(output, sidecar, o.input);
  std::optional<FrameChoice> frame;
  if (!o.frame.empty()) {
    frame = parseFrameChoice(o.frame);
    if (!frame)
      throw InputError(o.input,
                       "--frame '" + o.frame + "' must be a frame number (0, 1, ...) or 'mean'");
  }
  io::ReadOptions read;
  read.series = o.series;
  read.suv = !o.noSuv;
  Volume volume = fromStudy ? readStudyVolume(o, read) : io::readVolume(o.input, read);
  if (frame) volume = selectFrame(volume, *frame);
  const std::string text = sidecarJson(volume, o).dump(2) + "\n";

  // Both files appear or neither: they are written into a staging folder in the output's
  // folder and moved into place together; a failure on the way leaves what was there before.
  try {
    const fs::path folder = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    io::StagedFolder staging(folder,
                             {.purpose = "convert", .place = io::StagedFolder::Place::Inside});
    io::writeVolume(volume, staging.path() / output.filename());
    io::writeTextAtomically(staging.path() / sidecar.filename(), text);
    staging.commit({output.filename().string(), sidecar.filename().string()});
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // The output is a name the user typed: a place that cannot be written is bad input.
    throw InputError(output, std::string("cannot be written: ") + e.what());
  }
  const glm::ivec3 d = volume.dimensions();
  std::cout << "wrote " << output.string() << " (" << d.x << " x " << d.y << " x " << d.z;
  if (volume.components() > 1) std::cout << " x " << volume.components() << " frames";
  std::cout << ", " << scalarName(volume.scalarType())
            << (volume.metadata().unit.empty() ? "" : ", " + volume.metadata().unit) << ") and "
            << sidecar.string();
  if (fromStudy)
    std::cout << ": the " << (o.volume.empty() ? "anatomical" : o.volume) << " volume of "
              << o.input
              << (o.volume.empty() ? " (--volume functional|segmentation for the others)" : "");
  std::cout << "\n";
}

}  // namespace

void addConvertCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert",
      "Write a volume (DICOM series, NIfTI, MetaImage, or one volume of a study config) as NIfTI "
      "or MetaImage, in its physical unit and LPS geometry as every mvw command reads it, with a "
      "JSON sidecar (OUT.json)");
  cmd->add_option("input", opt->input,
                  "DICOM folder or file, NIfTI or MetaImage file, or a study config (.json)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "Output file: .nii.gz, .nii or .mha")->required();
  cmd->add_option("--series", opt->series,
                  "DICOM series, where the folder holds several: UID, number or part of the "
                  "description")
      ->check(nonEmpty());
  cmd->add_option("--frame", opt->frame,
                  "Of a 4D volume, write frame N (from 0) or 'mean' (default: every frame)")
      ->check(nonEmpty());
  cmd->add_option("--volume", opt->volume,
                  "Of a study config: anatomical (default), functional or segmentation")
      ->check(CLI::IsMember({"anatomical", "functional", "segmentation"}));
  cmd->add_flag("--no-suv", opt->noSuv, "Keep PET values in Bq/ml instead of converting to SUVbw");
  cmd->callback([opt, &pacs] {
    opt->pacs = pacs;
    runConvert(*opt);
  });
}

}  // namespace mvw::app
