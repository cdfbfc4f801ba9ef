#pragma once
// Statistics of a volume inside regions of interest, as a PET reader takes them: voxel count,
// volume, max, mean, SD, SUVpeak (PERCIST) and the metabolic volume above a threshold.
// ROIs are given in world coordinates (LPS mm) and hold the voxels whose centres lie inside.
// NaN voxels are "no data": counted apart and left out of every statistic. No GL here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"
#include "mvw/io/DicomSeg.h"

namespace mvw::study {

// Voxels of a volume by spatial index (k * ny + j) * nx + i, ascending.
using VoxelList = std::vector<std::size_t>;

struct SphereRoi {
  glm::dvec3 centre{0.0};  // LPS mm
  double radiusMm = 0.0;
};
struct BoxRoi {
  glm::dvec3 min{0.0}, max{0.0};  // opposite corners, LPS mm, min <= max on every axis
};

// The voxels whose centres lie inside. Bad input (radius <= 0, a box with min > max, an ROI
// that holds no voxel centre of the volume) throws InputError naming the volume's file.
VoxelList sphereVoxels(const Volume& volume, const SphereRoi& sphere);
VoxelList boxVoxels(const Volume& volume, const BoxRoi& box);

struct LabelRoi {
  int number = 0;
  std::string name;
  std::optional<std::array<std::uint8_t, 3>> rgb;
  VoxelList voxels;  // on the value volume's grid
};
struct LabelPlacement {
  std::vector<LabelRoi> labels;  // in the order of the SEG's segments / ascending label values
  bool gridsCoincide = false;    // every voxel of the value grid is a voxel of the label grid
  std::string note;              // how the labels were placed, for the report
};

// Segment masks placed onto `volume`'s grid by world position (nearest neighbour). A SEG on
// another frame of reference than the volume is refused (InputError naming the SEG).
LabelPlacement placeSegmentation(const Volume& volume, const io::Segmentation& segmentation);
// A label volume (integer values, 0 = background): each distinct non-zero value is a label.
LabelPlacement placeLabelVolume(const Volume& volume, const Volume& labels);

struct Threshold {
  enum class Kind { None, Absolute, FractionOfMax };
  Kind kind = Kind::None;
  double value = 0.0;  // the value, or the fraction of the ROI's max (0.41 for 41 %)
};

// PERCIST's SUVpeak sphere: 1 cm^3.
constexpr double kPeakRadiusMm = 6.204;

struct StatsOptions {
  Threshold threshold;
  bool peak = false;  // compute SUVpeak (for a unit where isSuvUnit is true)
};

// SUVbw, SUVlbm, ...: the units SUVpeak is defined for.
bool isSuvUnit(const std::string& unit);

struct RoiStats {
  std::size_t voxels = 0;                  // voxels with data
  std::size_t noData = 0;                  // NaN voxels in the ROI, left out
  double volumeMl = 0.0;                   // voxels * voxel volume
  double max = 0.0, mean = 0.0, sd = 0.0;  // sd: population standard deviation (divides by n)
  glm::dvec3 maxAt{0.0};                   // centre of the (first) hottest voxel, LPS mm
  std::string unit;
  // SUVpeak: the highest mean over the voxels (centres within kPeakRadiusMm, inside the volume,
  // with data, inside the ROI or not) of a sphere centred on a voxel of the ROI.
  std::optional<double> peak;
  glm::dvec3 peakAt{0.0};
  std::size_t peakSphereVoxels = 0;
  // With a threshold: the voxels of the ROI at or above it (the metabolic volume), their mean
  // (SUVmean of the metabolic volume; none without a voxel) and the total lesion glycolysis,
  // TLG = metabolic volume (ml) x its mean (0 without a voxel).
  std::optional<double> thresholdValue;
  std::size_t metabolicVoxels = 0;
  std::optional<double> metabolicVolumeMl;
  std::optional<double> metabolicMean;
  std::optional<double> tlg;
};

// Statistics of `volume` (component 0) over `voxels`; an ROI without voxels with data gives
// voxels == 0 and no max, mean, peak.
RoiStats roiStatistics(const Volume& volume, const VoxelList& voxels, const StatsOptions& options);

// The voxels of `voxels` with data at or above `threshold`, ascending.
VoxelList metabolicVoxels(const Volume& volume, const VoxelList& voxels, double threshold);

// The total metabolic tumour volume over several lesions (the segments of a SEG): the union of
// each lesion's metabolic voxels, each lesion taken at its own threshold (a fraction of its own
// max, as readers delineate lesion by lesion); a voxel in two lesions counts once. TLG is the
// union's volume x its mean, so it is the lesions' TLGs summed where they do not overlap.
struct MetabolicTotal {
  std::size_t voxels = 0;
  double volumeMl = 0.0;
  std::optional<double> mean;  // none without a voxel
  double tlg = 0.0;
};
MetabolicTotal metabolicTotal(const Volume& volume, const std::vector<VoxelList>& lesions,
                              const std::vector<double>& thresholds);

}  // namespace mvw::study
