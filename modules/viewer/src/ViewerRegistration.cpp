#include "mvw/viewer/ViewerRegistration.h"

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "mvw/resampling/RigidRegistration.h"

namespace mvw::viewer {

ViewerRegistration::ViewerRegistration(const Volume& anatomical, const Volume* functional,
                                       std::string description,
                                       resampling::RegistrationOptions options)
    : functional_(functional), description_(std::move(description)), affine_(options.affine) {
  job_ = [&anatomical, functional, options = std::move(options)](std::stop_token) {
    // registerRigid cannot be interrupted: a stop request waits for it to end.
    return resampling::registerRigid(anatomical, *functional, options);
  };
}

std::string ViewerRegistration::describePlacement(const std::string& method,
                                                  const nlohmann::json& report) {
  std::string text = method;
  if (report.contains("mutual_information"))
    text += ", MI " + std::to_string(report["mutual_information"].get<double>());
  return text;
}

void ViewerRegistration::start() {
  if (!functional_) return;
  worker_.start(job_);
}

std::optional<RegistrationWorker::Outcome> ViewerRegistration::finish() {
  std::optional<RegistrationWorker::Outcome> outcome = worker_.finish();
  if (!outcome || !outcome->result) return outcome;
  const resampling::RegistrationResult& r = *outcome->result;
  const std::string search =
      r.searchedRotations > 0 ? ", " + std::to_string(r.searchedRotations) + " rotations searched"
                              : "";
  description_ = std::string(r.affine ? "affine" : "rigid") + " (re-run" + search + "), MI " +
                 std::to_string(r.levels.empty() ? 0.0 : r.levels.back().metricEnd) +
                 (r.converged ? ", converged" : ", NOT converged") + ", " +
                 std::to_string(r.seconds).substr(0, 4) + " s";
  return outcome;
}

}  // namespace mvw::viewer
