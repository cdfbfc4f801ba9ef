#include "InfoCommand.h"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/VolumeReport.h"

namespace mvw::app {

namespace {

struct InfoOptions {
  std::vector<std::string> paths;
  std::string series;
  bool json = false;
  bool noSuv = false;
  std::size_t maxMemory = 0;  // bytes; 0: the reader's default (a quarter of physical RAM)
  pacs::Options pacs;         // the command line's --cache and time-outs (main.cpp)
};

void runInfo(const InfoOptions& opt) {
  io::ReadOptions read;
  read.series = opt.series;
  read.suv = !opt.noSuv;
  read.maxBytes = opt.maxMemory;
  const auto volumes =
      study::readReportedVolumes({opt.paths.begin(), opt.paths.end()}, read, opt.pacs);
  if (opt.json)
    std::cout << study::volumesJson(volumes).dump(2) << "\n";
  else
    study::printVolumes(std::cout, volumes);
}

}  // namespace

void addInfoCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Describe volumes: DICOM folders or files, NIfTI, MetaImage, or a study config (.json)");
  cmd->add_option("paths", opt->paths, "Files, DICOM folders or study configs")->required();
  cmd->add_option("--series", opt->series,
                  "DICOM series to show: UID, number or part of the description")
      ->check(nonEmpty());
  cmd->add_flag("--json", opt->json, "Print JSON instead of text");
  cmd->add_flag("--no-suv", opt->noSuv, "Keep PET values in Bq/ml instead of converting to SUVbw");
  cmd->add_option(
         "--max-memory", opt->maxMemory,
         "Refuse a volume larger than this in memory, checked on the header before anything is "
         "allocated (e.g. 512M, 4G; default: a quarter of physical RAM)")
      ->transform(CLI::AsSizeValue(false))
      ->check(CLI::Validator(io::maxBytesProblem, "SIZE"));  // after the transform: bytes
  cmd->callback([opt, &pacs] {
    opt->pacs = pacs;
    runInfo(*opt);
  });
}

}  // namespace mvw::app
