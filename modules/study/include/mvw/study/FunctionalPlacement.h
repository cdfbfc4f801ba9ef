#pragma once
// Where the study's functional volume lies on the anatomy: the study config's
// "registration" (none, rigid, affine, or an ITK transform file), shared by `mvw render` and
// `mvw view` so both place it the same way.
#include <nlohmann/json.hpp>

#include <glm/mat4x4.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"

namespace mvw::study {

struct FunctionalPlacement {
  glm::dmat4 anatomicalFromFunctional{1.0};
  nlohmann::json report;  // method, matrix, metric, iterations, seconds
};

FunctionalPlacement placeFunctional(const config::StudyConfig& study, const Volume& anatomical,
                                    const Volume& functional);

}  // namespace mvw::study
