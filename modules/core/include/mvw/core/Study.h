#pragma once
// A paired study: the anatomical volume (CT or T1 MRI) and, optionally, the functional one
// (PET, SPECT, fMRI, perfusion, dose, atlas labels) of the same patient.
#include <optional>
#include <string>

#include "mvw/core/Volume.h"

namespace mvw {

struct Study {
  std::string name;
  Volume anatomical;
  std::optional<Volume> functional;
};

}  // namespace mvw
