#pragma once
// A study config for the study module's tests (view planning, captions, defaults, glyphs):
// a CT with a PET beside it and one view, without files.
#include <optional>

#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"

namespace mvw::study {

// The anatomy ct.nii, the functional pet.nii, and the one view `view` (as a study.json's
// render.views[0]).
inline config::StudyConfig studyWith(const nlohmann::json& view) {
  config::StudyConfig s;
  s.file = "study.json";
  s.anatomical.path = "ct.nii";
  s.functional = config::VolumeSource{"pet.nii", "", "", "", std::nullopt};
  s.render.views = {config::parseViewConfig(view, s.file, "view", 0)};
  return s;
}

}  // namespace mvw::study
