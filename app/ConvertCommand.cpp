#include "ConvertCommand.h"

#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "mvw/study/VolumeConversion.h"
#include "mvw/study/VolumeReport.h"

namespace mvw::app {

namespace {

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

void runConvert(const ConvertOptions& o) {
  const bool fromStudy = study::isStudyConfig(o.input);
  if (fromStudy && !o.series.empty())
    throw CLI::ValidationError("--series", "chooses a DICOM series of a folder; the study config " +
                                               o.input + " names its series itself");
  if (fromStudy && !o.frame.empty())
    throw CLI::ValidationError("--frame", "chooses a frame of a volume file; the study config " +
                                              o.input + " chooses with its \"frame\"");
  if (!fromStudy && !o.volume.empty())
    throw CLI::ValidationError(
        "--volume", "chooses a volume of a study config (.json); " + o.input + " is a volume");
  const study::ConversionRequest request{.input = o.input,
                                         .output = o.output,
                                         .series = o.series,
                                         .frame = o.frame,
                                         .volume = o.volume,
                                         .suv = !o.noSuv};
  const std::filesystem::path sidecar = study::checkConversionOutput(request);
  const Volume volume = study::readConversionInput(request, o.pacs);
  const nlohmann::json json = study::conversionSidecar(study::volumeJson(volume), volume, request);
  study::writeConversion(volume, request.output, sidecar, json.dump(2) + "\n");
  std::cout << study::conversionSummary(volume, request, sidecar);
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
