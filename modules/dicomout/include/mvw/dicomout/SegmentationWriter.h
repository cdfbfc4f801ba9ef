#pragma once
// Masks on a volume's grid as a binary DICOM Segmentation (SEG): a frame for each slice that holds
// a voxel of a segment (empty frames are left out, as the SEG IOD allows), placed by its position
// and the grid's orientation, referencing the source image at the same position; segment
// category and type coded (SCT: Morphologically Altered Structure / Lesion or Neoplasm), the
// algorithm named.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/core/Volume.h"
#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SecondaryCapture.h"

namespace mvw::dicomout {

struct SegmentMask {
  std::string label;                // SegmentLabel; "" labels it by its type's code meaning
  std::string description;          // SegmentDescription ("" for none)
  std::vector<std::size_t> voxels;  // linear indices on the grid (Volume::linearIndex)
  bool metabolic = false;           // a threshold's metabolic volume: type Neoplasm, else Lesion
};

// `grid` gives dimensions and worldFromIndex (its voxels are not read). algorithm: the
// SegmentAlgorithmName (type SEMIAUTOMATIC). Throws InputError when no segment has a voxel.
void writeSegmentation(const std::filesystem::path& file, const Volume& grid,
                       const std::vector<SegmentMask>& segments, const DicomIdentity& source,
                       const SeriesInfo& series, const std::string& algorithm);

}  // namespace mvw::dicomout
