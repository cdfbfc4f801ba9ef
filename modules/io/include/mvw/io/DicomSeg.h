#pragma once
// DICOM Segmentation objects (SEG, SOP class 1.2.840.10008.5.1.4.1.1.66.4) as label masks
// placed in world coordinates (LPS mm). Segments may overlap, so each keeps its own mask: the
// masks volume has one component per segment. BINARY (1-bit packed) and FRACTIONAL (8-bit)
// segmentations are read; a FRACTIONAL voxel belongs to a segment from half the maximum
// fractional value up. Bad input throws mvw::InputError naming the file.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

namespace mvw::io {

struct Segment {
  int number = 0;           // SegmentNumber
  std::string label;        // SegmentLabel
  std::string description;  // SegmentDescription
  // RecommendedDisplayCIELabValue converted to sRGB (D65); empty when the SEG gives none.
  std::optional<std::array<std::uint8_t, 3>> rgb;
  int frames = 0;  // frames of the SEG that carry this segment
};

struct Segmentation {
  // uint8, one component per segment (component c belongs to segments[c]): 1 inside, 0 not.
  Volume masks;
  std::vector<Segment> segments;
  std::string type;  // BINARY or FRACTIONAL
  int frames = 0;    // NumberOfFrames of the SEG
  std::string frameOfReferenceUid;
};

// True for a DICOM file whose SOPClassUID is the Segmentation Storage class (reads the header
// only; false for folders and for files that are not DICOM).
bool isDicomSegmentation(const std::filesystem::path& path);

Segmentation readDicomSegmentation(const std::filesystem::path& path,
                                   const ReadOptions& options = {});

// One label per voxel, the segment number (uint8 or uint16); where segments overlap the voxel
// gets the highest number, and a note says how many voxels that concerns.
Volume labelVolume(const Segmentation& segmentation);

// CIELab as DICOM encodes it (L* 0..65535 -> 0..100, a* and b* 0..65535 -> -128..127) to sRGB.
std::array<std::uint8_t, 3> srgbFromDicomLab(std::uint16_t l, std::uint16_t a, std::uint16_t b);

}  // namespace mvw::io
