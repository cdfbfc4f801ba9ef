#include "mvw/study/RoiReport.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/io/DicomSeg.h"
#include "mvw/io/LabelTable.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/study/StudyLoader.h"

namespace mvw::study {

namespace {

namespace fs = std::filesystem;

std::string num(double v) { return shortNumber(v, 4); }
std::string mm(const glm::dvec3& p) {
  return fixedNumber(p.x, 1) + ", " + fixedNumber(p.y, 1) + ", " + fixedNumber(p.z, 1);
}

// Into report.rois: every label of a label volume or segment of a SEG (or the one asked for),
// on the volume's grid, named from the table beside a label volume. Returns whether they are
// every segment of a SEG (a total follows them).
bool addLabelRois(RoiReport& report, const Volume& volume, const RoiRequest& request,
                  const fs::path& source, const std::function<void(const std::string&)>& note) {
  const fs::path& file = request.labels;
  io::ReadOptions labelRead;
  const bool seg = io::isDicomSegmentation(file);
  LabelPlacement placed =
      seg ? placeSegmentation(volume, io::readDicomSegmentation(file, labelRead))
          : placeLabelVolume(volume, io::readVolume(file, labelRead));
  // A label volume's names from the table beside it (aal.nii.txt), as glyph views read them.
  // A table in another format (SPM's ROI_MNI_V4.txt: abbreviation, name, number) leaves the
  // labels numbered, with a note: the statistics do not depend on it.
  if (const auto table = seg ? std::nullopt : io::labelTableBeside(file)) {
    try {
      const std::map<int, std::string> names = io::readLabelTable(*table);
      for (auto& l : placed.labels)
        if (const auto it = names.find(l.number); it != names.end()) l.name = it->second;
    } catch (const InputError& e) {
      note(std::string("the label table beside the labels is not used: ") + e.what());
    }
  }
  report.placementNote = placed.note;
  std::vector<ReportedRoi>& rois = report.rois;
  std::string known;
  std::size_t listed = 0;
  for (const auto& l : placed.labels) {
    // The first 20 and the last (a CT given as labels has thousands of values).
    if (listed < 20 || &l == &placed.labels.back())
      known += (known.empty() ? "" : listed >= 20 ? ", ... " : ", ") + std::to_string(l.number);
    ++listed;
    if (request.label != 0 && l.number != request.label) continue;
    if (l.voxels.empty())
      throw InputError(file, "label " + std::to_string(l.number) + " (\"" + l.name +
                                 "\") covers no voxel centre of " + source.string());
    rois.push_back({"label " + std::to_string(l.number) + " \"" + l.name + "\"", l, l.voxels,
                    placed.gridsCoincide});
  }
  if (rois.empty())
    throw InputError(file, "no label " + std::to_string(request.label) + " (" +
                               std::to_string(placed.labels.size()) + " labels: " + known + ")");
  return seg && request.label == 0;
}

// The union of the segments and, with a threshold, their total metabolic tumour volume.
RoiTotal segmentTotal(const Volume& volume, const RoiReport& report) {
  RoiTotal total;
  total.segments = report.rois.size();
  total.what = "total over the " + std::to_string(report.rois.size()) + " segments";
  VoxelList all;
  std::vector<VoxelList> lesions;
  std::vector<double> thresholds;
  for (std::size_t i = 0; i < report.rois.size(); ++i) {
    all.insert(all.end(), report.rois[i].voxels.begin(), report.rois[i].voxels.end());
    if (report.stats[i].thresholdValue) {
      lesions.push_back(report.rois[i].voxels);
      thresholds.push_back(*report.stats[i].thresholdValue);
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  total.union_ = roiStatistics(volume, all, {});
  if (report.threshold.kind != Threshold::Kind::None)
    total.metabolic = metabolicTotal(volume, lesions, thresholds);
  return total;
}

nlohmann::json toJson(const ReportedRoi& roi, const RoiStats& s) {
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

nlohmann::json toJson(const RoiTotal& t) {
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

void printRoi(std::ostream& out, const ReportedRoi& roi, const RoiStats& s,
              const Threshold& threshold) {
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
    if (threshold.kind == Threshold::Kind::FractionOfMax)
      out << ", " << num(threshold.value * 100) << " % of max";
    out << ")\n";
    if (s.metabolicMean)
      out << "  metab. mean  " << num(*s.metabolicMean) << unit
          << "  (mean of the metabolic volume)\n";
    out << "  TLG          " << num(*s.tlg) << (unit.empty() ? " ml" : unit + " x ml")
        << "  (metabolic volume x its mean)\n";
  }
}

void printTotal(std::ostream& out, const RoiTotal& t) {
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

}  // namespace

Volume readMeasuredVolume(const fs::path& source, bool anatomical, const io::ReadOptions& options,
                          const pacs::Options& pacs) {
  if (!isStudyConfig(source)) return io::readVolume(source, options);
  const auto study = config::loadStudyConfig(source);
  if (anatomical) return readAnatomical(study.anatomical, options, pacs);
  if (!study.functional)
    throw InputError(source,
                     "the study names no functional volume (for its anatomical volume: --of "
                     "anatomical)");
  return readSource(*study.functional, options, pacs);
}

std::optional<RoiOptionProblem> roiOptionsProblem(const RoiOptions& o,
                                                  const RoiOptionNames& names) {
  const int rois = !o.sphere.empty() + !o.box.empty() + !o.labels.empty();
  if (rois > 1) return RoiOptionProblem{"ROI", roiChoice(names)};
  if (!std::isnan(o.threshold) && !std::isnan(o.thresholdFraction))
    return RoiOptionProblem{names.threshold, "give " + names.threshold + " or " +
                                                 names.thresholdFraction + ", not both"};
  if (!std::isnan(o.thresholdFraction) && !(o.thresholdFraction > 0 && o.thresholdFraction <= 1))
    return RoiOptionProblem{names.thresholdFraction, "must lie in (0, 1], e.g. 0.41", true};
  // With no ROI at all, the default label map (defaultLabels) is the labels the label is of.
  if (o.label != 0 && o.labels.empty() && rois != 0)
    return RoiOptionProblem{names.label, "needs " + names.labels, true};
  return std::nullopt;
}

std::string roiChoice(const RoiOptionNames& names) {
  return "give exactly one of " + names.sphere + ", " + names.box + " or " + names.labels;
}

fs::path studySegmentation(const fs::path& source, const pacs::Options& pacs) {
  if (!isStudyConfig(source)) return {};
  const auto study = config::loadStudyConfig(source);
  if (!study.segmentation) return {};
  if (study.segmentation->frame)
    throw InputError(source,
                     "its segmentation names a frame of a 4D label map; mvw stats "
                     "measures one whole label map: give it with --labels FILE");
  const fs::path path = localPath(*study.segmentation, pacs);
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return path;
  // A series folder (the PACS cache's holds its instances and the hidden list .complete).
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(path, ec))
    if (entry.is_regular_file(ec) && entry.path().filename().string().front() != '.')
      files.push_back(entry.path());
  if (files.size() != 1)
    throw InputError(path, "the study's segmentation holds " + countOf(files.size(), "file") +
                               ": mvw stats measures one DICOM SEG or label volume file: give "
                               "it with --labels FILE, or name an ROI");
  return files.front();
}

std::optional<DefaultLabels> defaultLabels(const Volume& volume, const fs::path& source,
                                           const pacs::Options& pacs) {
  const fs::path own = source.empty() ? fs::path() : studySegmentation(source, pacs);
  if (!own.empty())
    return DefaultLabels{own.string(), "the ROIs are the segments or labels of " + own.string() +
                                           " (the study's segmentation)"};
  const auto& segs = volume.metadata().segmentationFiles;
  if (segs.size() == 1)
    return DefaultLabels{segs.front(), "the ROIs are the segments of " + segs.front() +
                                           " (the DICOM SEG beside the series)"};
  return std::nullopt;
}

RoiRequest roiRequestOf(const RoiOptions& o) {
  RoiRequest request;
  if (!o.sphere.empty())
    request.sphere = SphereRoi{{o.sphere[0], o.sphere[1], o.sphere[2]}, o.sphere[3]};
  else if (!o.box.empty())
    request.box = BoxRoi{{o.box[0], o.box[1], o.box[2]}, {o.box[3], o.box[4], o.box[5]}};
  request.labels = o.labels;
  request.label = o.label;
  if (!std::isnan(o.threshold))
    request.threshold = {Threshold::Kind::Absolute, o.threshold};
  else if (!std::isnan(o.thresholdFraction))
    request.threshold = {Threshold::Kind::FractionOfMax, o.thresholdFraction};
  return request;
}

RoiReport roiReport(const Volume& volume, const RoiRequest& request, const fs::path& source,
                    const std::function<void(const std::string&)>& note) {
  RoiReport report;
  report.threshold = request.threshold;
  bool segmentList = false;  // every segment of a SEG: a total follows them
  if (request.sphere) {
    const SphereRoi& s = *request.sphere;
    report.rois.push_back(
        {"sphere at " + mm(s.centre) + " mm LPS, radius " + num(s.radiusMm) + " mm", std::nullopt,
         sphereVoxels(volume, s), false});
  } else if (request.box) {
    const BoxRoi& b = *request.box;
    report.rois.push_back({"box " + mm(b.min) + " .. " + mm(b.max) + " mm LPS", std::nullopt,
                           boxVoxels(volume, b), false});
  } else {
    segmentList = addLabelRois(report, volume, request, source, note);
  }

  // A PET left in Bq/ml says why (a threshold of 2.5 would otherwise be read as SUV 2.5).
  const auto& md = volume.metadata();
  if (md.modality == "PT" && !isSuvUnit(md.unit))
    for (const std::string& n : md.notes)
      if (n.find("SUV") != std::string::npos) note(source.string() + ": " + n);

  StatsOptions so;
  so.peak = isSuvUnit(md.unit);
  so.threshold = request.threshold;
  // Every ROI's numbers before any is reported. The one ROI asked for (a sphere, a box, one
  // label) holding only NaN (no data) is refused like one holding no voxel; among all the
  // labels of a map, such a label is listed with its count of NaN voxels.
  for (const auto& roi : report.rois) {
    report.stats.push_back(roiStatistics(volume, roi.voxels, so));
    if (report.stats.back().voxels == 0 && report.rois.size() == 1)
      throw InputError(source,
                       "the " + roi.what + " holds no voxel with data (its " +
                           countOf(static_cast<long long>(report.stats.back().noData), "voxel") +
                           (report.stats.back().noData == 1 ? " is" : " are") + " NaN)");
  }
  if (segmentList && report.rois.size() > 1) report.total = segmentTotal(volume, report);
  return report;
}

nlohmann::json roiReportJson(const RoiReport& report) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < report.rois.size(); ++i)
    out.push_back(toJson(report.rois[i], report.stats[i]));
  if (report.total) out.push_back(toJson(*report.total));
  return out;
}

void printRoiReport(std::ostream& out, const Volume& volume, const RoiReport& report) {
  const auto& md = volume.metadata();
  out << md.sourcePath;
  if (!md.seriesDescription.empty()) out << "  \"" << md.seriesDescription << "\"";
  out << "  (" << (md.modality.empty() ? "modality not stated" : md.modality)
      << (md.unit.empty() ? ", no unit" : ", values in " + md.unit) << ")\n";
  if (!report.placementNote.empty()) out << "  " << report.placementNote << "\n";
  for (std::size_t i = 0; i < report.rois.size(); ++i)
    printRoi(out, report.rois[i], report.stats[i], report.threshold);
  if (report.total) printTotal(out, *report.total);
}

RoiSegmentation roiSegmentation(const Volume& volume, const RoiReport& report) {
  RoiSegmentation out;
  const std::string unit = volume.metadata().unit.empty() ? "" : " " + volume.metadata().unit;
  out.algorithm = "mvw stats";
  std::string firstName;  // what the first segment is: its label, or the metabolic volume
  for (std::size_t i = 0; i < report.rois.size(); ++i) {
    const ReportedRoi& roi = report.rois[i];
    RoiSegment m;
    m.description = roi.what;
    if (const auto& threshold = report.stats[i].thresholdValue) {
      m.voxels = metabolicVoxels(volume, roi.voxels, *threshold);
      m.metabolic = true;
      // Labelled by its code (Neoplasm, dicomout); the threshold and the ROI describe it.
      const std::string name = "metabolic volume >= " + num(*threshold) + unit;
      m.description = name + " in " + roi.what;
      if (i == 0) firstName = name;
      out.algorithm =
          report.threshold.kind == Threshold::Kind::FractionOfMax
              ? "mvw stats, threshold " + num(report.threshold.value * 100) + " % of max"
              : "mvw stats, threshold " + num(report.threshold.value) + unit;
    } else {
      m.voxels = roi.voxels;
      m.label = roi.label ? roi.label->name : roi.what;
      if (i == 0) firstName = m.label;
      out.algorithm = "mvw stats, ROI";
    }
    out.segments.push_back(std::move(m));
  }
  out.seriesDescription =
      out.segments.size() == 1
          ? "mvw " + firstName
          : "mvw segmentation (" + std::to_string(out.segments.size()) + " segments)";
  return out;
}

}  // namespace mvw::study
