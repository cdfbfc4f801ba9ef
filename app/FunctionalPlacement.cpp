#include "FunctionalPlacement.h"

#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::app {

FunctionalPlacement placeFunctional(const config::StudyConfig& study, const Volume& anatomical,
                                    const Volume& functional) {
  FunctionalPlacement out;
  const config::RegistrationConfig& r = study.registration;
  out.report["method"] = r.method;
  if (r.method == "file") {
    const resampling::Transform t = resampling::Transform::readItk(r.transform);
    out.anatomicalFromFunctional = t.fixedFromMoving();
    out.report["transform_file"] = r.transform.string();
  } else if (r.method == "rigid" || r.method == "affine") {
    resampling::RegistrationOptions options;
    options.affine = r.method == "affine";
    options.rotationSearchRangeDeg = r.rotationSearchDeg;
    const resampling::RegistrationResult result =
        resampling::registerRigid(anatomical, functional, options);
    out.anatomicalFromFunctional = result.transform.fixedFromMoving();
    out.report["converged"] = result.converged;
    out.report["iterations"] = result.iterations;
    out.report["seconds"] = result.seconds;
    if (!result.levels.empty()) out.report["mutual_information"] = result.levels.back().metricEnd;
  }
  nlohmann::json rows = nlohmann::json::array();
  for (int row = 0; row < 4; ++row)
    rows.push_back({out.anatomicalFromFunctional[0][row], out.anatomicalFromFunctional[1][row],
                    out.anatomicalFromFunctional[2][row], out.anatomicalFromFunctional[3][row]});
  out.report["anatomical_from_functional"] = rows;
  return out;
}

}  // namespace mvw::app
