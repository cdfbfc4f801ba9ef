#include "mvw/study/FunctionalPlacement.h"

#include <cstdio>
#include <string>

#include "mvw/core/Error.h"
#include "mvw/render/Framing.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/resampling/Transform.h"

namespace mvw::study {

resampling::RegistrationOptions registrationOptionsOf(
    const config::RegistrationConfig& registration) {
  resampling::RegistrationOptions options;
  options.affine = registration.method == config::RegistrationMethod::Affine;
  options.rotationSearchRangeDeg = registration.rotationSearchDeg;
  return options;
}

FunctionalPlacement placeFunctional(const config::StudyConfig& study, const Volume& anatomical,
                                    const Volume& functional) {
  FunctionalPlacement out;
  const config::RegistrationConfig& r = study.registration;
  out.report["method"] = config::toString(r.method);
  if (r.method == config::RegistrationMethod::File) {
    const resampling::Transform t = resampling::Transform::readItk(r.transform);
    out.anatomicalFromFunctional = t.fixedFromMoving();
    out.report["transform_file"] = r.transform.string();
  } else if (r.method == config::RegistrationMethod::Rigid ||
             r.method == config::RegistrationMethod::Affine) {
    const resampling::RegistrationResult result =
        resampling::registerRigid(anatomical, functional, registrationOptionsOf(r));
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
  // Placed beside the anatomy, not on it: every view would show the anatomy alone (an empty
  // overlay, no glyphs) without a word. Wrong frames of reference or a wrong transform file.
  const auto [alo, ahi] = render::worldBounds(anatomical);
  const auto [flo, fhi] = render::worldBounds(functional, out.anatomicalFromFunctional);
  for (int a = 0; a < 3; ++a)
    if (fhi[a] < alo[a] || flo[a] > ahi[a]) {
      char text[400];
      std::snprintf(
          text, sizeof text,
          "as placed (registration \"%s\") it lies beside the anatomy, not on it: along %c "
          "it spans "
          "%.1f .. %.1f mm, the anatomical volume %.1f .. %.1f mm (do the two share a "
          "frame of reference? else register them)",
          config::toString(r.method).c_str(), "LPS"[a], flo[a], fhi[a], alo[a], ahi[a]);
      throw InputError(functional.metadata().sourcePath, text);
    }
  return out;
}

}  // namespace mvw::study
