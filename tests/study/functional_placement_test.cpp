// The one mapping from a study's "registration" to registerRigid's options
// (study::registrationOptionsOf), which placing the study, `mvw register STUDY.json` and the
// viewer's re-run share: the method and the rotation search carry over, nothing else moves off
// resampling's defaults.
#include <gtest/gtest.h>

#include "mvw/config/StudyConfig.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/study/FunctionalPlacement.h"

namespace mvw::study {
namespace {

using config::RegistrationMethod;

TEST(FunctionalPlacement, AffineAndTheRotationSearchMapToTheRegistrationOptions) {
  config::RegistrationConfig r;
  r.method = RegistrationMethod::Affine;
  r.rotationSearchDeg = 45.0;
  const resampling::RegistrationOptions options = registrationOptionsOf(r);
  const resampling::RegistrationOptions defaults;
  EXPECT_TRUE(options.affine);
  EXPECT_EQ(options.rotationSearchRangeDeg, 45.0);
  EXPECT_EQ(options.rotationSearchStepDeg, defaults.rotationSearchStepDeg);
  EXPECT_EQ(options.samples, defaults.samples);
  EXPECT_EQ(options.runs, defaults.runs);
  EXPECT_EQ(options.seed, defaults.seed);
  EXPECT_EQ(options.initialisation, defaults.initialisation);
}

// Rigid, and what a re-run of a study placed by a transform file or not at all registers.
TEST(FunctionalPlacement, EveryOtherMethodMapsToRigid) {
  for (RegistrationMethod method :
       {RegistrationMethod::Rigid, RegistrationMethod::None, RegistrationMethod::File}) {
    config::RegistrationConfig r;
    r.method = method;
    const resampling::RegistrationOptions options = registrationOptionsOf(r);
    EXPECT_FALSE(options.affine) << config::toString(method);
    EXPECT_EQ(options.rotationSearchRangeDeg, 0.0) << config::toString(method);
  }
}

}  // namespace
}  // namespace mvw::study
