// The registration re-run in the background: its line for the panel, a finished run moving the
// functional volume, a failed one saying why, and a running one that is waited for however the
// viewer ends (a joinable thread destroyed would terminate the process).
#include "mvw/viewer/ViewerRegistration.h"

#include <atomic>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "RegistrationTestUtil.h"
#include "TestUtil.h"
#include "ViewerTestUtil.h"
#include "mvw/viewer/ViewerScript.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {
namespace {

using ViewerRegistrationTest = ViewerFixture;

TEST(ViewerRegistration, DescribesThePlacement) {
  EXPECT_EQ(ViewerRegistration::describePlacement("none", nlohmann::json::object()), "none");
  EXPECT_EQ(ViewerRegistration::describePlacement("rigid", {{"mutual_information", 0.5}}),
            "rigid, MI 0.500000");
}

// A job that runs until the worker's thread is asked to stop (as a destructor does).
RegistrationWorker::Job untilStopped(std::atomic<bool>* started) {
  return [started](std::stop_token stop) {
    *started = true;
    while (!stop.stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return resampling::RegistrationResult{};
  };
}

void waitFor(const std::atomic<bool>& flag) {
  while (!flag) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

// With a std::thread member, each of these called std::terminate (a joinable thread destroyed).
TEST_F(ViewerRegistrationTest, DestroyedWhileRegisteringWaitsForTheWorker) {
  std::atomic<bool> started{false};
  {
    ViewerState state(study, ct, &pet, sceneOf(ct));
    state.registration().setJob(untilStopped(&started));
    state.registration().start();
    EXPECT_TRUE(state.registration().running());
    waitFor(started);
  }
  SUCCEED();
}

TEST_F(ViewerRegistrationTest, ScriptErrorWhileRegisteringUnwindsCleanly) {
  const auto dir = test::scratchDir();
  std::atomic<bool> started{false};
  const ViewerScript script = ViewerScript::parse(
      "register\nsave-config " + (dir / "missing" / "folder" / "state.json").string() + "\n",
      dir / "script");
  auto run = [&] {
    ViewerState state(study, ct, &pet, sceneOf(ct));
    state.registration().setJob(untilStopped(&started));
    ViewerScript s = script;
    EXPECT_TRUE(s.step(state));  // register
    EXPECT_TRUE(state.registration().running());
    waitFor(started);
    s.step(state);  // save-config into a folder that does not exist: throws
  };
  EXPECT_THROW(run(), std::exception);
}

TEST_F(ViewerRegistrationTest, FinishedRegistrationMovesTheFunctionalVolume) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  renderAll(state);
  const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 3.0));
  state.registration().setJob([moved](std::stop_token) {
    resampling::RegistrationResult r;
    r.transform = resampling::Transform(moved);
    r.converged = true;
    r.seconds = 1.25;
    return r;
  });
  state.registration().start();
  std::optional<glm::dmat4> placed;
  while (state.registration().running() && !(placed = state.finishRegistration()))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(placed);
  EXPECT_EQ(*placed, moved);
  EXPECT_FALSE(state.registration().running());
  EXPECT_EQ(state.registration().description(), "rigid (re-run), MI 0.000000, converged, 1.25 s");
  EXPECT_TRUE(state.needsRender(k3d) && state.needsRender(kAxial));
}

// The re-run registers as the study asks (issue 48: it always ran rigid with the default
// options): an affine study with a rotation search, re-run by the script's `register`, reports
// an affine result that searched rotations.
TEST(ViewerRegistration, ScriptReRunsAnAffineStudyAffine) {
  config::StudyConfig study;
  study.registration.method = config::RegistrationMethod::Affine;
  study.registration.rotationSearchDeg = 30.0;
  const Volume ct = resampling::blobs({0.0, 0.0, 0.0});
  const Volume pet = resampling::blobs({4.0, -3.0, 2.0});
  ViewerState state(study, ct, &pet, sceneOf(ct));
  EXPECT_STREQ(state.registration().method(), "affine");
  ViewerScript script =
      ViewerScript::parse("register\nwait-registration\n", test::scratchDir() / "script");
  // As the window loop does: a line a frame, and a run that ended applied before the next.
  std::optional<glm::dmat4> placed;
  while (script.step(state)) {
    if (auto p = state.finishRegistration()) placed = p;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(placed) << state.requests().status();
  const std::string& description = state.registration().description();
  EXPECT_EQ(description.rfind("affine (re-run, ", 0), 0u) << description;
  EXPECT_NE(description.find(" rotations searched), MI "), std::string::npos) << description;
}

TEST_F(ViewerRegistrationTest, FailedRegistrationSaysWhy) {
  ViewerState state(study, ct, &pet, sceneOf(ct));
  state.registration().setJob([](std::stop_token) -> resampling::RegistrationResult {
    throw std::runtime_error("no overlap");
  });
  state.registration().start();
  while (state.registration().running()) {
    EXPECT_EQ(state.finishRegistration(), std::nullopt);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(state.requests().status(), "registration failed: no overlap");
  EXPECT_EQ(state.registration().description(), "none");
}

}  // namespace
}  // namespace mvw::viewer
