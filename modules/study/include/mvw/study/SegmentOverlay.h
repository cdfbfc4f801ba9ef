#pragma once
// The study's "segmentation" as MPR outlines: a DICOM SEG (its segments, names and colours) or
// a label volume (one segment per non-zero value, at most 16, colours from a fixed palette).
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/pacs/Pacs.h"

namespace mvw::study {

struct SegmentOverlay {
  Volume masks;  // uint8, one component per segment, 1 inside
  std::vector<int> numbers;
  std::vector<std::string> names;
  std::vector<glm::vec3> colours;  // sRGB 0..1
};

// Bad input (not a SEG or label volume, more than 16 labels) throws InputError naming the file.
// A PACS series is read from the verified cache with `pacs` (study::localPath).
SegmentOverlay readSegmentOverlay(const config::VolumeSource& source,
                                  const io::ReadOptions& options, const pacs::Options& pacs);

// Where the segmentation lies on the anatomy: with the functional volume's placement when
// both state the same frame of reference (a SEG drawn on the PET), by world coordinates
// otherwise.
glm::dmat4 anatomicalFromSegmentation(const SegmentOverlay& overlay, const Volume* functional,
                                      const glm::dmat4& anatomicalFromFunctional);

}  // namespace mvw::study
