#pragma once
// Renders as Secondary Capture: a still as an SC image (RGB, the PNG's pixels exactly), an
// orbit as one Multi-frame True Color SC (frames in order, with a frame time), in the study of
// the anatomical source, referencing its images.
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/core/Image.h"
#include "mvw/dicomout/DicomIdentity.h"

namespace mvw::dicomout {

struct SeriesInfo {
  std::string seriesInstanceUid;  // empty: a new one
  int seriesNumber = 0;
  std::string description;  // SeriesDescription
};

struct CaptureInfo {
  int instanceNumber = 1;
  bool burnedInAnnotation = false;  // labels, captions or legends drawn into the pixels
  double frameTimeMs = 0.0;         // multi-frame only: milliseconds between frames
  std::string derivation;           // DerivationDescription: how the image was made
};

// One frame: Secondary Capture Image Storage; several: Multi-frame True Color Secondary
// Capture Image Storage. Every frame the same size; alpha is dropped. Written to a temporary
// name and renamed; throws mvw::Error naming the file if it cannot be written.
void writeSecondaryCapture(const std::filesystem::path& file, const std::vector<Image>& frames,
                           const DicomIdentity& source, const SeriesInfo& series,
                           const CaptureInfo& info);

}  // namespace mvw::dicomout
