#include "StatsCommand.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "DicomOutput.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/dicomout/SegmentationWriter.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/RoiReport.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct StatsOptions {
  std::string source;
  std::string series;
  std::string of;  // "" = functional, for a study config; refused for a volume file
  study::RoiOptions roi;
  bool json = false;
  bool noSuv = false;
  std::string seg;  // --seg OUT.dcm
  DicomOutputOptions dicom;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

// --seg: the ROIs (or their metabolic volumes) as a binary DICOM SEG on the volume's grid, in
// the source's study (study::roiSegmentation).
void writeSeg(const StatsOptions& opt, const Volume& volume, const study::RoiReport& report) {
  const dicomout::DicomIdentity id = dicomout::identityOf(volume, opt.dicom.given());
  study::RoiSegmentation plan = study::roiSegmentation(volume, report);
  std::vector<dicomout::SegmentMask> segments;
  for (auto& s : plan.segments)
    segments.push_back({s.label, s.description, std::move(s.voxels), s.metabolic});
  dicomout::SeriesInfo series;
  series.seriesNumber = 3001;
  series.description = plan.seriesDescription;
  dicomout::writeSegmentation(opt.seg, volume, segments, id, series, plan.algorithm);
  std::cerr << "mvw stats: wrote the DICOM SEG " << opt.seg << " ("
            << countOf(static_cast<long long>(segments.size()), "segment") << ") "
            << identityNote(id) << "\n";
}

void runStats(StatsOptions opt) {
  const int rois = (!opt.roi.sphere.empty()) + (!opt.roi.box.empty()) + (!opt.roi.labels.empty());
  if (const auto problem = study::roiOptionsProblem(opt.roi))
    throw CLI::ValidationError(problem->option, problem->problem);
  checkDicomOutput(opt.dicom, !opt.seg.empty(), {});
  if (!opt.seg.empty()) {
    std::error_code ec;
    const fs::path parent = fs::absolute(opt.seg).parent_path();
    if (!fs::is_directory(parent, ec))
      throw InputError(opt.seg, "its folder " + parent.string() + " does not exist");
    if (fs::is_directory(opt.seg, ec)) throw InputError(opt.seg, "is a folder, not a file name");
  }
  const fs::path source(opt.source);
  if (source.extension() != ".json" && !opt.of.empty())
    throw CLI::ValidationError(
        "--of", "chooses a volume of a study config (.json); " + source.string() + " is a volume");

  io::ReadOptions read;
  read.series = opt.series;
  read.suv = !opt.noSuv;
  const Volume volume = study::readMeasuredVolume(source, opt.of == "anatomical", read, opt.pacs);
  // Without an ROI: the study config's own segmentation, or the one DICOM SEG beside the
  // series in its folder (as `mvw info` lists it).
  if (rois == 0) {
    const auto labels = study::defaultLabels(volume, source, opt.pacs);
    if (!labels) throw CLI::ValidationError("ROI", study::roiChoice());
    opt.roi.labels = labels->path;
    std::cerr << "mvw stats: note: " << labels->note << "\n";
  }

  const study::RoiReport report = study::roiReport(
      volume, study::roiRequestOf(opt.roi), source,
      [](const std::string& note) { std::cerr << "mvw stats: note: " << note << "\n"; });
  if (!opt.seg.empty()) writeSeg(opt, volume, report);
  if (opt.json)
    std::cout << study::roiReportJson(report).dump(2) << "\n";
  else
    study::printRoiReport(std::cout, volume, report);
  // The SEG, written and the statistics said: to the server (said on stderr, as the SEG is).
  if (!opt.seg.empty()) storeDicom(opt.dicom, opt.pacs, {opt.seg}, opt.seg, std::cerr);
}

}  // namespace

void addStatsCommand(CLI::App& app, const pacs::Options& pacs) {
  auto opt = std::make_shared<StatsOptions>();
  // Coordinates, radii and thresholds: finite numbers only (NaN would pass every comparison).
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && std::isfinite(v)) return "";
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number";
      },
      "NUMBER");
  CLI::App* cmd = app.add_subcommand(
      "stats",
      "Statistics in a region of interest (LPS mm) or per label: voxels, volume, max, mean, SD, "
      "SUVpeak and the metabolic volume for PET in SUV");
  cmd->add_option("source", opt->source, "Volume (file or DICOM folder) or study config (.json)")
      ->required();
  cmd->add_option("--series", opt->series, "DICOM series: UID, number or part of the description")
      ->check(nonEmpty());
  cmd->add_option("--of", opt->of, "With a study config: which volume (default functional)")
      ->check(CLI::IsMember({"anatomical", "functional"}));
  cmd->add_option("--sphere", opt->roi.sphere, "Sphere X Y Z R: centre in LPS mm, radius in mm")
      ->expected(4)
      ->check(finite);
  cmd->add_option("--box", opt->roi.box, "Box X0 Y0 Z0 X1 Y1 Z1: opposite corners in LPS mm")
      ->expected(6)
      ->check(finite);
  cmd->add_option("--labels", opt->roi.labels,
                  "Label map: a DICOM SEG (one ROI per segment) or a label volume (one per value); "
                  "default: the SEG beside a folder's one image series")
      ->check(nonEmpty());
  cmd->add_option("--label", opt->roi.label, "Only this label (segment number; 0 is no label)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return std::strtol(text.c_str(), nullptr, 10) != 0
                       ? std::string()
                       : "0 is no label (the background), not '" + text + "'";
          },
          "LABEL"));
  cmd->add_option("--threshold", opt->roi.threshold,
                  "Metabolic volume: voxels at or above this value (e.g. 2.5 for SUV 2.5)")
      ->check(finite);
  cmd->add_option("--threshold-fraction", opt->roi.thresholdFraction,
                  "Metabolic volume: voxels at or above this fraction of the ROI's max (e.g. 0.41)")
      ->check(finite);
  cmd->add_flag("--json", opt->json, "Print a JSON array, one object per ROI or label");
  cmd->add_flag("--no-suv", opt->noSuv, "Keep PET values in Bq/ml instead of converting to SUVbw");
  cmd->add_option(
         "--seg", opt->seg,
         "Write the ROI (with --threshold/--threshold-fraction: its metabolic volume) as a "
         "binary DICOM SEG file on the volume's grid")
      ->check(nonEmpty());
  addDicomOptions(*cmd, opt->dicom, false);
  cmd->callback([opt, &pacs] {
    opt->pacs = pacs;
    runStats(*opt);
  });
}

}  // namespace mvw::app
