#pragma once
// ROI statistics as `mvw stats` reports them: the ROIs a request names (a sphere, a box, every
// label of a label volume or segment of a DICOM SEG, or one of them), each one's statistics
// (RoiStatistics.h), the total over a SEG's segments (their union, the total metabolic tumour
// volume and its TLG), as JSON for a script and as text for a person, and the segments of the
// DICOM SEG that writes the ROIs back (written by dicomout, which study does not reach).
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"
#include "mvw/study/RoiStatistics.h"

namespace mvw::study {

// The volume `mvw stats` measures: a volume file, or a study config's (.json) functional volume
// (readSource), or with `anatomical` its anatomical one (readAnatomical). A study without a
// functional volume throws InputError naming the config.
Volume readMeasuredVolume(const std::filesystem::path& source, bool anatomical,
                          const io::ReadOptions& options, const pacs::Options& pacs);

// Exactly one of sphere, box and labels.
struct RoiRequest {
  std::optional<SphereRoi> sphere;
  std::optional<BoxRoi> box;
  std::filesystem::path labels;  // a DICOM SEG (one ROI per segment) or a label volume
  int label = 0;                 // only this label or segment; 0: every one
  Threshold threshold;           // the metabolic volume's, if any
};

// The ROI options of `mvw stats` as given: --sphere X Y Z R and --box X0 Y0 Z0 X1 Y1 Z1 (empty:
// not given), --labels, --label, --threshold and --threshold-fraction (NaN: not given).
struct RoiOptions {
  std::vector<double> sphere, box;
  std::string labels;
  int label = 0;
  double threshold = std::numeric_limits<double>::quiet_NaN();
  double thresholdFraction = std::numeric_limits<double>::quiet_NaN();
};

// How a caller's users spell those options: the command line's flags, or mvw.stats's Python
// arguments.
struct RoiOptionNames {
  std::string sphere = "--sphere X Y Z R", box = "--box X0 Y0 Z0 X1 Y1 Z1",
              labels = "--labels FILE", threshold = "--threshold",
              thresholdFraction = "--threshold-fraction", label = "--label";
};

// What is wrong with ROI options as given, the one home of these rules for `mvw stats` and
// mvw.stats: at most one of sphere, box and labels; a threshold or a fraction of the maximum, not
// both; a fraction in (0, 1]; a label only of labels (given, or none: the default label map). The
// option it concerns ("ROI" for the choice) and the problem, in `names`; nothing when they hold.
// `ofOption`: the problem is said of the option ("must lie in ...", "needs ..."), so a sentence
// puts the option's name before it; otherwise it is a whole sentence ("give exactly one of ...").
struct RoiOptionProblem {
  std::string option, problem;
  bool ofOption = false;
};
std::optional<RoiOptionProblem> roiOptionsProblem(const RoiOptions& o,
                                                  const RoiOptionNames& names = {});
// "give exactly one of ...": the ROI choice, said in `names`.
std::string roiChoice(const RoiOptionNames& names = {});

// The label map a study config's own "segmentation" gives `mvw stats` when no ROI is named: its
// file, or the one file of its series (a DICOM SEG from a folder or the PACS, retrieved into the
// verified cache with `pacs`); empty for a volume file or a study without a segmentation. One
// that names a frame of a 4D label map, or a series folder holding more or fewer than one
// file, throws InputError naming it and asking for --labels: stats measures one whole file.
std::filesystem::path studySegmentation(const std::filesystem::path& source,
                                        const pacs::Options& pacs);

// The label map `mvw stats` and mvw.stats measure when no ROI is named, the one home of that
// choice: a study config's own segmentation (studySegmentation; `source` is the config, or
// empty), else the one DICOM SEG beside the volume's DICOM series (its metadata's
// segmentationFiles); with the note that tells the user which. Nothing when neither.
struct DefaultLabels {
  std::string path, note;
};
std::optional<DefaultLabels> defaultLabels(const Volume& volume,
                                           const std::filesystem::path& source,
                                           const pacs::Options& pacs);

// The request of those options (checked first by roiOptionsProblem).
RoiRequest roiRequestOf(const RoiOptions& o);

struct ReportedRoi {
  std::string what;  // "sphere at ...", "box ...", or "label N \"name\""
  std::optional<LabelRoi> label;
  VoxelList voxels;
  bool gridsCoincide = false;  // labels: the label grid is the volume's, voxel for voxel
};

// The total over a SEG's segments: their union's voxels and, with a threshold, the total
// metabolic tumour volume (metabolicTotal).
struct RoiTotal {
  std::string what;  // "total over the N segments"
  std::size_t segments = 0;
  RoiStats union_;
  std::optional<MetabolicTotal> metabolic;
};

struct RoiReport {
  std::string placementNote;  // how the labels were placed on the volume's grid ("" for none)
  Threshold threshold;
  std::vector<ReportedRoi> rois;
  std::vector<RoiStats> stats;    // one per ROI
  std::optional<RoiTotal> total;  // every segment of a SEG with more than one
};

// The statistics of `volume` over the ROIs `request` names, SUVpeak where the volume's unit is
// an SUV. `source` names the volume in messages (the file or study config the user gave).
// Bad input throws InputError: a label that is not in the map, or covers no voxel centre; the
// one ROI asked for (a sphere, a box, one label) holding only NaN (no data). `note` hears, as
// they arise, what the user should know but does not stop the report: a label table beside the
// labels that cannot be read, a PET left in Bq/ml and why.
RoiReport roiReport(const Volume& volume, const RoiRequest& request,
                    const std::filesystem::path& source,
                    const std::function<void(const std::string&)>& note);

// The report as a JSON array: one object per ROI, then the total.
nlohmann::json roiReportJson(const RoiReport& report);
// The report as text: a line naming the volume (its file, description, modality and unit), the
// placement note, then a block of lines per ROI and the total.
void printRoiReport(std::ostream& out, const Volume& volume, const RoiReport& report);

// One segment of the SEG `mvw stats --seg` writes: an ROI, or with a threshold its metabolic
// volume (dicomout::SegmentMask's fields). A metabolic volume has no label of its own (the SEG
// labels it by its code) and says its threshold and ROI in the description.
struct RoiSegment {
  std::string label, description;
  VoxelList voxels;
  bool metabolic = false;
};
struct RoiSegmentation {
  std::vector<RoiSegment> segments;  // one per ROI
  std::string algorithm;             // the SegmentAlgorithmName
  std::string seriesDescription;
};
RoiSegmentation roiSegmentation(const Volume& volume, const RoiReport& report);

}  // namespace mvw::study
