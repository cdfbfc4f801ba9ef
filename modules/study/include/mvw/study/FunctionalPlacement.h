#pragma once
// Where the study's functional volume lies on the anatomy: the study config's
// "registration" (none, rigid, affine, or an ITK transform file), shared by `mvw render` and
// `mvw view` so both place it the same way; and the registration options those settings ask
// for, the one mapping `mvw register STUDY.json` and the viewer's re-run use too.
#include <nlohmann/json.hpp>

#include <glm/mat4x4.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Volume.h"
#include "mvw/resampling/RigidRegistration.h"

namespace mvw::study {

struct FunctionalPlacement {
  glm::dmat4 anatomicalFromFunctional{1.0};
  nlohmann::json report;  // method, matrix, metric, iterations, seconds
};

// What a study's "registration" asks of resampling::registerRigid: rigid, or rigid then affine,
// with its rotation search. One mapping, so that placing the study, `mvw register STUDY.json`
// (whose flags override it) and the viewer's re-run register alike. Everything the config does
// not name keeps resampling's default. A transform file or none maps to rigid: what a re-run
// of such a study registers.
resampling::RegistrationOptions registrationOptionsOf(
    const config::RegistrationConfig& registration);

FunctionalPlacement placeFunctional(const config::StudyConfig& study, const Volume& anatomical,
                                    const Volume& functional);

}  // namespace mvw::study
