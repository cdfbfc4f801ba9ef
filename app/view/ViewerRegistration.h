#pragma once
// The registration re-run the panel's button and the script's `register` start: rigid mutual
// information as `mvw register`, on RegistrationWorker's thread so the window keeps drawing,
// and the panel's line for the placement in use. It knows the two volumes and nothing of the
// viewer's state: ViewerState::finishRegistration applies a run that ended (the functional
// volume's new placement, the status line on failure).
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "RegistrationWorker.h"
#include "mvw/core/Volume.h"

namespace mvw::app {

class ViewerRegistration {
 public:
  // The volumes must outlive this (a running job reads them). `description`: the study's own
  // placement as the panel shows it (ViewerScene::registration).
  ViewerRegistration(const Volume& anatomical, const Volume* functional, std::string description);
  ~ViewerRegistration() = default;  // a running job is waited for, never abandoned
  ViewerRegistration(const ViewerRegistration&) = delete;
  ViewerRegistration& operator=(const ViewerRegistration&) = delete;

  // Starts a re-run; nothing without a functional volume or while one runs.
  void start();
  bool running() const { return worker_.running(); }
  double seconds() const { return worker_.seconds(); }  // since the running one started
  // Once a re-run has ended: its outcome (a result, or the error that stopped it); after a
  // result description() names the run. Nothing while it runs, or when none ran.
  std::optional<RegistrationWorker::Outcome> finish();
  // The study's placement as describePlacement words it until a re-run ends, then the run's
  // ("rigid (re-run), MI 0.512345, converged, 3.12 s").
  const std::string& description() const { return description_; }
  // The panel's line for the study's placement (placeFunctional's method and report).
  static std::string describePlacement(const std::string& method, const nlohmann::json& report);
  // For tests: the job start() runs instead of registerRigid.
  void setJob(RegistrationWorker::Job job) { job_ = std::move(job); }

 private:
  const Volume* functional_;
  std::string description_;
  RegistrationWorker::Job job_;
  RegistrationWorker worker_;  // last: joined before the job (and what it reads) goes away
};

}  // namespace mvw::app
