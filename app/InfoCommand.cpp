#include "InfoCommand.h"

#include <cerrno>
#include <cstdlib>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "VolumeReport.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/StudyLoader.h"

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

bool isStudyConfig(const std::filesystem::path& p) { return p.extension() == ".json"; }

void runInfo(const InfoOptions& opt) {
  // Read everything first: a bad input anywhere means no partial report.
  struct Item {
    std::string role;
    Volume volume;
  };
  std::vector<Item> items;
  io::ReadOptions read;
  read.series = opt.series;
  read.suv = !opt.noSuv;
  read.maxBytes = opt.maxMemory;
  for (const auto& p : opt.paths) {
    if (isStudyConfig(p)) {
      const auto study = config::loadStudyConfig(p);
      items.push_back({"anatomical", mvw::study::readSource(study.anatomical, read, opt.pacs)});
      if (study.functional)
        items.push_back({"functional (" + config::toString(study.functionalKind) + ")",
                         mvw::study::readSource(*study.functional, read, opt.pacs)});
    } else {
      for (auto& v : io::readAllVolumes(p, read)) items.push_back({"", std::move(v)});
    }
  }
  if (opt.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : items) {
      auto j = volumeJson(item.volume);
      if (!item.role.empty()) j["role"] = item.role;
      out.push_back(j);
    }
    std::cout << out.dump(2) << "\n";
    return;
  }
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) std::cout << "\n";
    if (!items[i].role.empty()) std::cout << "[" << items[i].role << "] ";
    printVolume(std::cout, items[i].volume);
  }
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
      ->check(CLI::Validator(
          [](std::string& text) {
            // After the transform: a byte count. 1 MiB .. 1 PiB; beyond 2^64 the text is no
            // longer a number CLI11 could convert.
            errno = 0;
            char* end = nullptr;
            const unsigned long long bytes = std::strtoull(text.c_str(), &end, 10);
            if (errno != 0 || end == text.c_str() || *end != '\0' || bytes < (1ull << 20) ||
                bytes > (1ull << 50))
              return std::string("must be a size from 1M to 1P (e.g. 512M, 4G)");
            return std::string();
          },
          "SIZE"));
  cmd->callback([opt, &pacs] {
    opt->pacs = pacs;
    runInfo(*opt);
  });
}

}  // namespace mvw::app
