#include "StatsCommand.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "CliChecks.h"
#include "DicomOutput.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/dicomout/SegmentationWriter.h"
#include "mvw/io/DicomSeg.h"
#include "mvw/io/LabelTable.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/RoiStatistics.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct StatsOptions {
  std::string source;
  std::string series;
  std::string of;  // "" = functional, for a study config; refused for a volume file
  std::vector<double> sphere, box;
  std::string labels;
  int label = 0;
  double threshold = NAN, thresholdFraction = NAN;
  bool json = false;
  bool noSuv = false;
  std::string seg;  // --seg OUT.dcm
  DicomOutputOptions dicom;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

std::string num(double v, int significant = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}
std::string mm(const glm::dvec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.1f, %.1f, %.1f", p.x, p.y, p.z);
  return buf;
}

struct Roi {
  std::string what;  // "sphere ...", "box ...", or the label's name
  std::optional<study::LabelRoi> label;
  study::VoxelList voxels;
  bool gridsCoincide = false;  // labels: the label grid is the volume's, voxel for voxel
};

nlohmann::json toJson(const Roi& roi, const study::RoiStats& s) {
  nlohmann::json j;
  j["roi"] = roi.what;
  if (roi.label) {
    j["label"] = roi.label->number;
    j["name"] = roi.label->name;
    j["grids_coincide"] = roi.gridsCoincide;
    if (roi.label->rgb)
      j["rgb"] = {(*roi.label->rgb)[0], (*roi.label->rgb)[1], (*roi.label->rgb)[2]};
  }
  j["voxels"] = s.voxels;
  j["voxels_no_data"] = s.noData;
  j["volume_ml"] = s.volumeMl;
  j["unit"] = s.unit;
  if (s.voxels) {
    j["max"] = s.max;
    j["max_at_lps_mm"] = {s.maxAt.x, s.maxAt.y, s.maxAt.z};
    j["mean"] = s.mean;
    j["sd"] = s.sd;
  } else {
    j["max"] = j["mean"] = j["sd"] = nullptr;
  }
  if (s.peak) {
    j["peak"] = *s.peak;
    j["peak_at_lps_mm"] = {s.peakAt.x, s.peakAt.y, s.peakAt.z};
    j["peak_sphere_voxels"] = s.peakSphereVoxels;
  }
  if (s.thresholdValue) {
    j["threshold"] = *s.thresholdValue;
    j["metabolic_voxels"] = s.metabolicVoxels;
    j["metabolic_volume_ml"] = *s.metabolicVolumeMl;
    j["metabolic_mean"] = s.metabolicMean ? nlohmann::json(*s.metabolicMean) : nullptr;
    j["tlg"] = *s.tlg;
  }
  return j;
}

// The total over a SEG's segments: their union's voxels and, with a threshold, the total
// metabolic tumour volume (study::metabolicTotal).
struct Total {
  std::string what;
  std::size_t segments = 0;
  study::RoiStats union_;
  std::optional<study::MetabolicTotal> metabolic;
};

nlohmann::json toJson(const Total& t) {
  nlohmann::json j;
  j["roi"] = t.what;
  j["total"] = true;
  j["segments"] = t.segments;
  j["voxels"] = t.union_.voxels;
  j["voxels_no_data"] = t.union_.noData;
  j["volume_ml"] = t.union_.volumeMl;
  j["unit"] = t.union_.unit;
  j["max"] = t.union_.voxels ? nlohmann::json(t.union_.max) : nullptr;
  j["mean"] = t.union_.voxels ? nlohmann::json(t.union_.mean) : nullptr;
  if (t.metabolic) {
    j["metabolic_voxels"] = t.metabolic->voxels;
    j["metabolic_volume_ml"] = t.metabolic->volumeMl;
    j["metabolic_mean"] = t.metabolic->mean ? nlohmann::json(*t.metabolic->mean) : nullptr;
    j["tlg"] = t.metabolic->tlg;
  }
  return j;
}

void printText(std::ostream& out, const Roi& roi, const study::RoiStats& s,
               const StatsOptions& opt) {
  const std::string unit = s.unit.empty() ? "" : " " + s.unit;
  out << roi.what << "\n";
  out << "  voxels       " << s.voxels << "  (" << num(s.volumeMl) << " ml)";
  if (s.noData) out << ", " << s.noData << " without data (NaN) left out";
  out << "\n";
  if (!s.voxels) return;
  out << "  max          " << num(s.max) << unit << "  at " << mm(s.maxAt) << " mm LPS\n";
  out << "  mean         " << num(s.mean) << unit << "\n";
  out << "  sd           " << num(s.sd) << unit << "\n";
  if (s.peak)
    out << "  peak         " << num(*s.peak) << unit << "  (1 cm^3 sphere at " << mm(s.peakAt)
        << " mm LPS, " << s.peakSphereVoxels << " voxels)\n";
  if (s.thresholdValue) {
    out << "  metabolic    " << num(*s.metabolicVolumeMl) << " ml  (" << s.metabolicVoxels
        << " voxels >= " << num(*s.thresholdValue) << unit;
    if (!std::isnan(opt.thresholdFraction))
      out << ", " << num(opt.thresholdFraction * 100) << " % of max";
    out << ")\n";
    if (s.metabolicMean)
      out << "  metab. mean  " << num(*s.metabolicMean) << unit
          << "  (mean of the metabolic volume)\n";
    out << "  TLG          " << num(*s.tlg) << (unit.empty() ? " ml" : unit + " x ml")
        << "  (metabolic volume x its mean)\n";
  }
}

void printText(std::ostream& out, const Total& t) {
  const std::string unit = t.union_.unit.empty() ? "" : " " + t.union_.unit;
  out << t.what << "\n";
  out << "  voxels       " << t.union_.voxels << "  (" << num(t.union_.volumeMl) << " ml)\n";
  if (t.union_.voxels) {
    out << "  max          " << num(t.union_.max) << unit << "\n";
    out << "  mean         " << num(t.union_.mean) << unit << "\n";
  }
  if (!t.metabolic) return;
  out << "  TMTV         " << num(t.metabolic->volumeMl) << " ml  (" << t.metabolic->voxels
      << " voxels, each segment at its own threshold)\n";
  if (t.metabolic->mean) out << "  metab. mean  " << num(*t.metabolic->mean) << unit << "\n";
  out << "  TLG          " << num(t.metabolic->tlg) << (unit.empty() ? " ml" : unit + " x ml")
      << "  (total metabolic tumour volume x its mean)\n";
}

// --seg: each ROI, or with a threshold its metabolic volume, as one segment of a binary DICOM
// SEG on the volume's grid, in the source's study.
void writeSeg(const StatsOptions& opt, const Volume& volume, const std::vector<Roi>& list,
              const std::vector<study::RoiStats>& stats, const study::StatsOptions& so) {
  const dicomout::DicomIdentity id = dicomout::identityOf(volume, opt.dicom.given());
  std::vector<dicomout::SegmentMask> segments;
  const std::string unit = volume.metadata().unit.empty() ? "" : " " + volume.metadata().unit;
  std::string algorithm = "mvw stats";
  for (std::size_t i = 0; i < list.size(); ++i) {
    dicomout::SegmentMask m;
    m.description = list[i].what;
    if (stats[i].thresholdValue) {
      m.voxels = study::metabolicVoxels(volume, list[i].voxels, *stats[i].thresholdValue);
      m.metabolic = true;
      m.label = "metabolic volume >= " + num(*stats[i].thresholdValue) + unit;
      algorithm = so.threshold.kind == study::Threshold::Kind::FractionOfMax
                      ? "mvw stats, threshold " + num(opt.thresholdFraction * 100) + " % of max"
                      : "mvw stats, threshold " + num(opt.threshold) + unit;
    } else {
      m.voxels = list[i].voxels;
      m.label = list[i].label ? list[i].label->name : list[i].what;
      algorithm = "mvw stats, ROI";
    }
    segments.push_back(std::move(m));
  }
  dicomout::SeriesInfo series;
  series.seriesNumber = 3001;
  series.description = segments.size() == 1
                           ? "mvw " + segments.front().label
                           : "mvw segmentation (" + std::to_string(segments.size()) + " segments)";
  dicomout::writeSegmentation(opt.seg, volume, segments, id, series, algorithm);
  std::cerr << "mvw stats: wrote the DICOM SEG " << opt.seg << " (" << segments.size() << " segment"
            << (segments.size() == 1 ? "" : "s") << ") " << identityNote(id) << "\n";
}

void printStats(const Volume& volume, const std::string& placementNote,
                const std::vector<Roi>& list, const std::vector<study::RoiStats>& stats,
                const std::optional<Total>& total, const StatsOptions& opt) {
  const auto& md = volume.metadata();
  std::cout << md.sourcePath;
  if (!md.seriesDescription.empty()) std::cout << "  \"" << md.seriesDescription << "\"";
  std::cout << "  (" << (md.modality.empty() ? "modality not stated" : md.modality)
            << (md.unit.empty() ? ", no unit" : ", values in " + md.unit) << ")\n";
  if (!placementNote.empty()) std::cout << "  " << placementNote << "\n";
  for (std::size_t i = 0; i < list.size(); ++i) printText(std::cout, list[i], stats[i], opt);
  if (total) printText(std::cout, *total);
}

void runStats(StatsOptions opt) {
  const int rois = (!opt.sphere.empty()) + (!opt.box.empty()) + (!opt.labels.empty());
  const char* kRoiChoice =
      "give exactly one of --sphere X Y Z R, --box X0 Y0 Z0 X1 Y1 Z1 or --labels FILE";
  if (rois > 1) throw CLI::ValidationError("ROI", kRoiChoice);
  if (!std::isnan(opt.threshold) && !std::isnan(opt.thresholdFraction))
    throw CLI::ValidationError("--threshold", "give --threshold or --threshold-fraction, not both");
  if (!std::isnan(opt.thresholdFraction) &&
      !(opt.thresholdFraction > 0 && opt.thresholdFraction <= 1))
    throw CLI::ValidationError("--threshold-fraction", "must lie in (0, 1], e.g. 0.41");
  if (opt.label != 0 && opt.labels.empty() && rois != 0)
    throw CLI::ValidationError("--label", "needs --labels FILE");
  checkDicomOutput(opt.dicom, !opt.seg.empty(), {});
  if (!opt.seg.empty()) {
    std::error_code ec;
    const fs::path parent = fs::absolute(opt.seg).parent_path();
    if (!fs::is_directory(parent, ec))
      throw InputError(opt.seg, "its folder " + parent.string() + " does not exist");
    if (fs::is_directory(opt.seg, ec)) throw InputError(opt.seg, "is a folder, not a file name");
  }

  io::ReadOptions read;
  read.series = opt.series;
  read.suv = !opt.noSuv;
  Volume volume;
  const fs::path source(opt.source);
  if (source.extension() == ".json") {
    const auto study = config::loadStudyConfig(source);
    if (opt.of == "anatomical") {
      volume = study::readAnatomical(study.anatomical, read, opt.pacs);
    } else {
      if (!study.functional)
        throw InputError(source,
                         "the study names no functional volume (for its anatomical volume: "
                         "--of anatomical)");
      volume = study::readSource(*study.functional, read, opt.pacs);
    }
  } else {
    if (!opt.of.empty())
      throw CLI::ValidationError("--of", "chooses a volume of a study config (.json); " +
                                             source.string() + " is a volume");
    volume = io::readVolume(source, read);
  }
  // A folder of one image series and its DICOM SEG: without an ROI, the SEG's segments are the
  // ROIs (as `mvw info` lists the SEG beside the series).
  if (rois == 0) {
    const auto& segs = volume.metadata().segmentationFiles;
    if (segs.size() != 1) throw CLI::ValidationError("ROI", kRoiChoice);
    opt.labels = segs.front();
    std::cerr << "mvw stats: note: the ROIs are the segments of " << opt.labels
              << " (the DICOM SEG beside the series)\n";
  }
  if (opt.label != 0 && opt.labels.empty())
    throw CLI::ValidationError("--label", "needs --labels FILE");

  std::vector<Roi> list;
  std::string placementNote;
  bool segmentList = false;  // every segment of a SEG: a total follows them
  if (!opt.sphere.empty()) {
    const study::SphereRoi s{{opt.sphere[0], opt.sphere[1], opt.sphere[2]}, opt.sphere[3]};
    list.push_back({"sphere at " + mm(s.centre) + " mm LPS, radius " + num(s.radiusMm) + " mm",
                    std::nullopt, study::sphereVoxels(volume, s), false});
  } else if (!opt.box.empty()) {
    const study::BoxRoi b{{opt.box[0], opt.box[1], opt.box[2]},
                          {opt.box[3], opt.box[4], opt.box[5]}};
    list.push_back({"box " + mm(b.min) + " .. " + mm(b.max) + " mm LPS", std::nullopt,
                    study::boxVoxels(volume, b), false});
  } else {
    const fs::path file(opt.labels);
    io::ReadOptions labelRead;
    const bool seg = io::isDicomSegmentation(file);
    study::LabelPlacement placed =
        seg ? study::placeSegmentation(volume, io::readDicomSegmentation(file, labelRead))
            : study::placeLabelVolume(volume, io::readVolume(file, labelRead));
    // A label volume's names from the table beside it (aal.nii.txt), as glyph views read them.
    // A table in another format (SPM's ROI_MNI_V4.txt: abbreviation, name, number) leaves the
    // labels numbered, with a note: the statistics do not depend on it.
    if (const auto table = seg ? std::nullopt : io::labelTableBeside(file)) {
      try {
        const std::map<int, std::string> names = io::readLabelTable(*table);
        for (auto& l : placed.labels)
          if (const auto it = names.find(l.number); it != names.end()) l.name = it->second;
      } catch (const InputError& e) {
        std::cerr << "mvw stats: note: the label table beside the labels is not used: " << e.what()
                  << "\n";
      }
    }
    placementNote = placed.note;
    segmentList = seg && opt.label == 0;
    bool found = false;
    std::string known;
    std::size_t listed = 0;
    for (const auto& l : placed.labels) {
      // The first 20 and the last (a CT given as labels has thousands of values).
      if (listed < 20 || &l == &placed.labels.back())
        known += (known.empty() ? "" : listed >= 20 ? ", ... " : ", ") + std::to_string(l.number);
      ++listed;
      if (opt.label != 0 && l.number != opt.label) continue;
      found = true;
      if (l.voxels.empty())
        throw InputError(file, "label " + std::to_string(l.number) + " (\"" + l.name +
                                   "\") covers no voxel centre of " + opt.source);
      list.push_back({"label " + std::to_string(l.number) + " \"" + l.name + "\"", l, l.voxels,
                      placed.gridsCoincide});
    }
    if (!found)
      throw InputError(file, "no label " + std::to_string(opt.label) + " (" +
                                 std::to_string(placed.labels.size()) + " labels: " + known + ")");
  }

  // A PET left in Bq/ml says why (a threshold of 2.5 would otherwise be read as SUV 2.5).
  if (volume.metadata().modality == "PT" && !study::isSuvUnit(volume.metadata().unit))
    for (const std::string& note : volume.metadata().notes)
      if (note.find("SUV") != std::string::npos)
        std::cerr << "mvw stats: note: " << opt.source << ": " << note << "\n";

  study::StatsOptions so;
  so.peak = study::isSuvUnit(volume.metadata().unit);
  if (!std::isnan(opt.threshold))
    so.threshold = {study::Threshold::Kind::Absolute, opt.threshold};
  else if (!std::isnan(opt.thresholdFraction))
    so.threshold = {study::Threshold::Kind::FractionOfMax, opt.thresholdFraction};

  // Every ROI's numbers before any is printed. The one ROI asked for (a sphere, a box, one
  // label) holding only NaN (no data) is refused like one holding no voxel, with nothing on
  // stdout; among all the labels of a map, such a label is listed with its count of NaN voxels.
  std::vector<study::RoiStats> stats;
  for (const auto& roi : list) {
    stats.push_back(study::roiStatistics(volume, roi.voxels, so));
    if (stats.back().voxels == 0 && list.size() == 1)
      throw InputError(source, "the " + roi.what + " holds no voxel with data (its " +
                                   std::to_string(stats.back().noData) + " voxels are NaN)");
  }
  if (!opt.seg.empty()) writeSeg(opt, volume, list, stats, so);
  std::optional<Total> total;
  if (segmentList && list.size() > 1) {
    total.emplace();
    total->segments = list.size();
    total->what = "total over the " + std::to_string(list.size()) + " segments";
    study::VoxelList all;
    std::vector<study::VoxelList> lesions;
    std::vector<double> thresholds;
    for (std::size_t i = 0; i < list.size(); ++i) {
      all.insert(all.end(), list[i].voxels.begin(), list[i].voxels.end());
      if (stats[i].thresholdValue) {
        lesions.push_back(list[i].voxels);
        thresholds.push_back(*stats[i].thresholdValue);
      }
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    total->union_ = study::roiStatistics(volume, all, {});
    if (so.threshold.kind != study::Threshold::Kind::None)
      total->metabolic = study::metabolicTotal(volume, lesions, thresholds);
  }
  if (opt.json) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t i = 0; i < list.size(); ++i) out.push_back(toJson(list[i], stats[i]));
    if (total) out.push_back(toJson(*total));
    std::cout << out.dump(2) << "\n";
  } else {
    printStats(volume, placementNote, list, stats, total, opt);
  }
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
  cmd->add_option("--sphere", opt->sphere, "Sphere X Y Z R: centre in LPS mm, radius in mm")
      ->expected(4)
      ->check(finite);
  cmd->add_option("--box", opt->box, "Box X0 Y0 Z0 X1 Y1 Z1: opposite corners in LPS mm")
      ->expected(6)
      ->check(finite);
  cmd->add_option("--labels", opt->labels,
                  "Label map: a DICOM SEG (one ROI per segment) or a label volume (one per value); "
                  "default: the SEG beside a folder's one image series")
      ->check(nonEmpty());
  cmd->add_option("--label", opt->label, "Only this label (segment number; 0 is no label)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return std::strtol(text.c_str(), nullptr, 10) != 0
                       ? std::string()
                       : "0 is no label (the background), not '" + text + "'";
          },
          "LABEL"));
  cmd->add_option("--threshold", opt->threshold,
                  "Metabolic volume: voxels at or above this value (e.g. 2.5 for SUV 2.5)")
      ->check(finite);
  cmd->add_option("--threshold-fraction", opt->thresholdFraction,
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
