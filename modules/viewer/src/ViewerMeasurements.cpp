#include "mvw/viewer/ViewerMeasurements.h"

#include <cmath>
#include <utility>

#include <nlohmann/json.hpp>

#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::viewer {

namespace {

glm::dvec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> arr(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json statsJson(const std::optional<study::RoiStats>& s, const std::string& problem) {
  nlohmann::json j;
  if (!s) {
    j["problem"] = problem;
    return j;
  }
  j["voxels"] = s->voxels;
  j["voxels_no_data"] = s->noData;
  j["volume_ml"] = s->volumeMl;
  j["unit"] = s->unit;
  if (s->voxels) {
    j["max"] = s->max;
    j["max_at_lps_mm"] = {s->maxAt.x, s->maxAt.y, s->maxAt.z};
    j["mean"] = s->mean;
    j["sd"] = s->sd;
  }
  if (s->peak) {
    j["peak"] = *s->peak;
    j["peak_at_lps_mm"] = {s->peakAt.x, s->peakAt.y, s->peakAt.z};
  }
  return j;
}

}  // namespace

ViewerMeasurements::ViewerMeasurements(const PaneGeometry& panes, const Volume& anatomical,
                                       const Volume* functional,
                                       const glm::dmat4& anatomicalFromFunctional)
    : panes_(panes),
      anatomical_(anatomical),
      functional_(functional),
      anatomicalFromFunctional_(anatomicalFromFunctional) {}

SphereStatistics ViewerMeasurements::computeStatistics(
    const config::SphereMeasurement& sphere) const {
  SphereStatistics out;
  auto one = [&](const Volume& v, const glm::dvec3& centre, std::optional<study::RoiStats>& stats,
                 std::string& problem) {
    try {
      study::StatsOptions options;
      options.peak = study::isSuvUnit(v.metadata().unit);  // as `mvw stats` asks
      stats = study::roiStatistics(v, study::sphereVoxels(v, {centre, sphere.radiusMm}), options);
    } catch (const InputError& e) {
      problem = e.problem();
    }
  };
  one(anatomical_, vec(sphere.centre), out.anatomical, out.anatomicalProblem);
  if (functional_) {
    // A rigid placement keeps the radius; the centre moves into the functional world.
    out.functionalCentre =
        glm::dvec3(glm::inverse(anatomicalFromFunctional_) * glm::dvec4(vec(sphere.centre), 1.0));
    one(*functional_, out.functionalCentre, out.functional, out.functionalProblem);
  }
  return out;
}

void ViewerMeasurements::addSphere(const config::SphereMeasurement& sphere) {
  measurements_.spheres.push_back(sphere);
  sphereStats_.push_back(computeStatistics(sphere));
}

void ViewerMeasurements::addRuler(const config::RulerMeasurement& ruler) {
  measurements_.rulers.push_back(ruler);
}

void ViewerMeasurements::clear() {
  measurements_ = {};
  sphereStats_.clear();
  pending_.reset();
}

void ViewerMeasurements::setPlacement(const glm::dmat4& anatomicalFromFunctional) {
  anatomicalFromFunctional_ = anatomicalFromFunctional;
  for (std::size_t i = 0; i < sphereStats_.size(); ++i)  // the functional ROI moved with it
    sphereStats_[i] = computeStatistics(measurements_.spheres[i]);
}

double ViewerMeasurements::rulerLengthMm(const config::RulerMeasurement& r) {
  return glm::distance(vec(r.from), vec(r.to));
}

void ViewerMeasurements::beginGesture(int pane, MprTool tool, double x, double y) {
  if (pane == k3d || tool == MprTool::Crosshair) return;
  const glm::dvec3 p = panes_.onPlane(pane, x, y);
  pending_ = Gesture{pane, tool, p, p};
}

void ViewerMeasurements::moveGesture(double x, double y) {
  if (pending_) pending_->to = panes_.onPlane(pending_->pane, x, y);
}

void ViewerMeasurements::endGesture() {
  if (!pending_) return;
  const Gesture g = *std::exchange(pending_, std::nullopt);
  const double length = glm::distance(g.from, g.to);
  if (length <= 0.0) return;  // a click: nothing to measure
  if (g.tool == MprTool::Sphere)
    addSphere({arr(g.from), length});
  else
    addRuler({arr(g.from), arr(g.to)});
}

std::optional<config::SphereMeasurement> ViewerMeasurements::pendingSphere() const {
  if (!pending_ || pending_->tool != MprTool::Sphere) return std::nullopt;
  return config::SphereMeasurement{arr(pending_->from),
                                   glm::distance(pending_->from, pending_->to)};
}

std::optional<config::RulerMeasurement> ViewerMeasurements::pendingRuler() const {
  if (!pending_ || pending_->tool != MprTool::Ruler) return std::nullopt;
  return config::RulerMeasurement{arr(pending_->from), arr(pending_->to)};
}

glm::dvec2 ViewerMeasurements::toPane(int pane, const glm::dvec3& world) const {
  const glm::dvec4 c = panes_.paneCamera(pane).clipFromWorld * glm::dvec4(world, 1.0);
  return {(c.x / c.w + 1.0) * 0.5, (1.0 - c.y / c.w) * 0.5};
}

std::optional<PaneCircle> ViewerMeasurements::paneCircle(
    int pane, const config::SphereMeasurement& sphere) const {
  if (pane == k3d || !panes_.paneRendered(pane)) return std::nullopt;
  const render::Camera& cam = panes_.paneCamera(pane);
  const glm::dvec3 centre = vec(sphere.centre);
  const double d = glm::dot(centre - panes_.crosshair(), cam.forward);  // from the pane's plane
  if (std::abs(d) >= sphere.radiusMm) return std::nullopt;
  PaneCircle c;
  c.radiusMm = std::sqrt(sphere.radiusMm * sphere.radiusMm - d * d);
  const glm::dvec3 onPlane = centre - d * cam.forward;
  c.centre = toPane(pane, onPlane);
  c.radius = glm::abs(glm::dvec2(toPane(pane, onPlane + c.radiusMm * cam.right).x - c.centre.x,
                                 toPane(pane, onPlane + c.radiusMm * cam.up).y - c.centre.y));
  return c;
}

PaneSegment ViewerMeasurements::paneSegment(int pane, const config::RulerMeasurement& ruler) const {
  PaneSegment s;
  if (pane == k3d || !panes_.paneRendered(pane)) return s;
  const render::Camera& cam = panes_.paneCamera(pane);
  s.from = toPane(pane, vec(ruler.from));
  s.to = toPane(pane, vec(ruler.to));
  const double half = 0.5 * anatomical_.smallestSpacing();
  const glm::dvec3& crosshair = panes_.crosshair();
  s.inPlane = std::abs(glm::dot(vec(ruler.from) - crosshair, cam.forward)) <= half &&
              std::abs(glm::dot(vec(ruler.to) - crosshair, cam.forward)) <= half;
  return s;
}

void ViewerMeasurements::writeSphereStatistics(const std::filesystem::path& file) const {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < sphereStats_.size(); ++i) {
    const config::SphereMeasurement& s = measurements_.spheres[i];
    const SphereStatistics& st = sphereStats_[i];
    nlohmann::json j;
    j["sphere"] = {s.centre[0], s.centre[1], s.centre[2], s.radiusMm};
    j["anatomical"] = statsJson(st.anatomical, st.anatomicalProblem);
    if (functional_) {
      j["functional"] = statsJson(st.functional, st.functionalProblem);
      j["functional_centre_lps_mm"] = {st.functionalCentre.x, st.functionalCentre.y,
                                       st.functionalCentre.z};
    }
    out.push_back(j);
  }
  io::writeTextAtomically(file, out.dump(2) + "\n");
}

}  // namespace mvw::viewer
