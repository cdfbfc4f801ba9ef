#pragma once
// The registration re-run the panel's button and the script's `register` start: mutual
// information with the options the study's "registration" maps to (study::
// registrationOptionsOf: rigid or rigid then affine, the rotation search), as placing the
// study and `mvw register STUDY.json` register, on RegistrationWorker's thread so the window
// keeps drawing, and the panel's line for the placement in use. It knows the two volumes and
// nothing of the viewer's state: ViewerState::finishRegistration applies a run that ended (the
// functional volume's new placement, the status line on failure).
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/Volume.h"
#include "mvw/resampling/RigidRegistration.h"
#include "mvw/viewer/RegistrationWorker.h"

namespace mvw::viewer {

class ViewerRegistration {
 public:
  // The volumes must outlive this (a running job reads them). `description`: the study's own
  // placement as the panel shows it (ViewerScene::registration); `options`: what a re-run asks
  // of registerRigid.
  ViewerRegistration(const Volume& anatomical, const Volume* functional, std::string description,
                     resampling::RegistrationOptions options);
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
  // ("rigid (re-run), MI 0.512345, converged, 3.12 s"; "affine (re-run, 27 rotations
  // searched), ..." after a rotation search and an affine stage).
  const std::string& description() const { return description_; }
  // What a re-run registers, for the panel's button: "rigid" or "affine".
  const char* method() const { return affine_ ? "affine" : "rigid"; }
  // The panel's line for the study's placement (placeFunctional's method and report).
  static std::string describePlacement(const std::string& method, const nlohmann::json& report);
  // For tests: the job start() runs instead of registerRigid.
  void setJob(RegistrationWorker::Job job) { job_ = std::move(job); }

 private:
  const Volume* functional_;
  std::string description_;
  bool affine_ = false;
  RegistrationWorker::Job job_;
  RegistrationWorker worker_;  // last: joined before the job (and what it reads) goes away
};

}  // namespace mvw::viewer
