#include "mvw/viewer/ViewerState.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>

#include "mvw/core/WindowLevel.h"
#include "mvw/io/LabelTable.h"
#include "mvw/io/Png.h"
#include "mvw/render/TransferFunction.h"
#include "mvw/study/Caption.h"
#include "mvw/study/FunctionalPlacement.h"
#include "mvw/study/ModalityDefaults.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"
#include "mvw/viewer/ViewControls.h"

namespace mvw::viewer {

namespace {

using render::RenderMode;
using render::StandardView;

const char* kPaneNames[kPaneCount] = {"3d", "axial", "coronal", "sagittal"};
// The PET/CT layout's names of the same slots (scripts may use either).
const char* kPetCtPaneNames[kPaneCount] = {"mip", "anatomical", "functional", "fused"};
const StandardView kMprViews[3] = {StandardView::Inferior, StandardView::Anterior,
                                   StandardView::Left};
const RenderMode k3dModes[] = {RenderMode::Composite, RenderMode::Isosurface, RenderMode::Mip,
                               RenderMode::MinIp, RenderMode::Average};

constexpr double kMinMprZoom = 0.1, kMaxMprZoom = 50.0;

bool is3dMode(RenderMode mode) {
  return std::find(std::begin(k3dModes), std::end(k3dModes), mode) != std::end(k3dModes);
}

// Nearest voxel: the readout names a voxel's stored value, not an interpolation.
double sampleAt(const Volume& v, const glm::dvec3& world, bool* inside) {
  const glm::dvec3 ijk = glm::dvec3(glm::inverse(v.worldFromIndex()) * glm::dvec4(world, 1.0));
  const glm::ivec3 n(std::lround(ijk.x), std::lround(ijk.y), std::lround(ijk.z));
  *inside = glm::all(glm::greaterThanEqual(n, glm::ivec3(0))) &&
            glm::all(glm::lessThan(n, v.dimensions()));
  return *inside ? v.value(n.x, n.y, n.z) : 0.0;
}

// As the renderer's linear 3D texture: trilinear between voxel centres, clamped to the edge
// voxels, inside the voxel box (half a voxel beyond the outer centres).
double sampleLinear(const Volume& v, const glm::dvec3& world, bool* inside) {
  const glm::dvec3 ijk = glm::dvec3(glm::inverse(v.worldFromIndex()) * glm::dvec4(world, 1.0));
  const glm::dvec3 n(v.dimensions());
  *inside = glm::all(glm::greaterThanEqual(ijk, glm::dvec3(-0.5))) &&
            glm::all(glm::lessThanEqual(ijk, n - 0.5));
  if (!*inside) return 0.0;
  const glm::dvec3 c = glm::clamp(ijk, glm::dvec3(0.0), n - 1.0);
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(c)), v.dimensions() - 1);
  const glm::ivec3 i1 = glm::min(i0 + 1, v.dimensions() - 1);
  const glm::dvec3 t = c - glm::dvec3(i0);
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 b((corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0);
    const double w = (b.x ? t.x : 1 - t.x) * (b.y ? t.y : 1 - t.y) * (b.z ? t.z : 1 - t.z);
    if (w == 0.0) continue;
    sum += w * v.value(b.x ? i1.x : i0.x, b.y ? i1.y : i0.y, b.z ? i1.z : i0.z);
  }
  return sum;
}

std::string formatValue(double v, const std::string& unit) {
  char buf[64];
  std::snprintf(buf, sizeof buf, std::abs(v) >= 100 ? "%.0f" : "%.3g", v);
  return std::string(buf) + (unit.empty() ? " (no unit)" : " " + unit);
}

}  // namespace

ViewerState::ViewerState(const config::StudyConfig& study, const Volume& anatomical,
                         const Volume* functional, ViewerScene scene)
    : study_(study),
      anatomical_(anatomical),
      functional_(functional),
      scene_(std::move(scene)),
      // The measurements see the panes through this state's PaneGeometry (asked nothing of it
      // until the state is built).
      measurements_(*this, anatomical, functional, scene_.anatomicalFromFunctional),
      registration_(anatomical, functional, scene_.registration,
                    mvw::study::registrationOptionsOf(study.registration)) {
  const mvw::study::ModalityDefaults defaults =
      mvw::study::modalityDefaults(anatomical_, scene_.valueRange);
  presetName_ = defaults.preset;
  view3d_.transfer = render::transferPreset(presetName_);
  view3d_.camera.view = StandardView::Anterior;
  view3d_.iso = defaults.iso;
  view3d_.cutFace = CutFace::Anatomy;  // as a planned view has it by default (cut_face)
  if (defaults.mode3d != RenderMode::Composite) {
    // A PET read alone (study::modalityDefaults): its MIP under its own window, as the implied
    // view of a config without views has it (study::applyModalityView).
    view3d_.mode = defaults.mode3d;
    view3d_.window = defaults.mpr;
    if (defaults.mipColors != ColorMap::Grey)
      view3d_.imageColors = mvw::study::colorTable(defaults.mipColors);
  }
  mprWindow_ = defaults.mpr;
  crosshair_ = scene_.centre;
  functionalColors_ = greyTable(true);  // PET as nuclear medicine reads it: black on white
  // The study's first view the 3D pane can show sets it up, exactly as `mvw render` would
  // render it (glyphs, attribute window, crop, light, ...); an MPR view sets the MPR panes'
  // window and the overlay.
  std::vector<mvw::study::PlannedView> planned = mvw::study::planViews(study_);
  mvw::study::prepareViews(planned, study_, anatomical_, functional_, scene_.functionalRange);
  for (const mvw::study::PlannedView& v : planned) {
    if (!is3dMode(v.settings.mode)) continue;
    view3d_ = v.settings;
    glyphScaleView_ = v.config;
    glyphScaleSpacingMm_ = glyphSpacingMm(view3d_);
    presetName_ = v.presetName;
    // A view in another mode carries the config's default isovalue (300, for HU): key 2 would
    // show nothing on a volume that does not reach it (a PET in SUV), so the volume's own.
    const auto [lo, hi] = scene_.valueRange;
    if (v.settings.mode != RenderMode::Isosurface && !(view3d_.iso > lo && view3d_.iso < hi))
      view3d_.iso = defaults.iso;
    break;
  }
  if (functional_) {
    functionalDisplay_ =
        mvw::study::defaultFunctionalDisplayWindow(*functional_, scene_.functionalRange);
  }
  for (const mvw::study::PlannedView& v : planned)
    if (v.settings.mode == RenderMode::Mpr) {
      if (v.config.functionalWindow.set()) functionalDisplay_ = v.config.functionalWindow;
      if (v.settings.window.set()) mprWindow_ = v.settings.window;
      mprColors_ = v.settings.imageColors;
      segmentOutlines_ = v.settings.segmentationOutlines;
      break;
    }
  // A saved state's MPR panes (views named view-axial, ...): their zoom, and the linked pan
  // from their pans (each sees the world pan's two in-plane components; every axis is seen by
  // two of the three panes). A study's own MPR views keep their zoom for `mvw render`: it is
  // set for their image's shape (a portrait whole body), not for the viewer's panes.
  glm::dvec3 pan(0.0);
  for (const mvw::study::PlannedView& v : planned)
    if (v.settings.mode == RenderMode::Mpr && v.config.name.rfind("view-", 0) == 0) {
      mprZoom_ = std::clamp(v.settings.camera.zoom, kMinMprZoom, kMaxMprZoom);
      const render::Camera cam =
          render::makeCamera(v.settings.camera, scene_.centre, scene_.radius, {64, 64});
      pan += 0.5 * (cam.right * v.settings.camera.panMm.x + cam.up * v.settings.camera.panMm.y);
    }
  mprPan_ = pan;
  if (study_.functionalKind == config::FunctionalKind::Labels && study_.functional)
    if (auto table = io::labelTableBeside(study_.functional->path))
      labelNames_ = io::readLabelTable(*table);
  for (const config::SphereMeasurement& sphere : study_.measurements.spheres)
    measurements_.addSphere(sphere);
  for (const config::RulerMeasurement& ruler : study_.measurements.rulers)
    measurements_.addRuler(ruler);
  setLayout(study_.layout);
}

const char* ViewerState::paneName(int pane) { return kPaneNames[pane]; }

std::optional<int> ViewerState::paneNamed(const std::string& name) {
  for (int p = 0; p < kPaneCount; ++p)
    if (name == kPaneNames[p] || name == kPetCtPaneNames[p]) return p;
  return std::nullopt;
}

void ViewerState::setLayout(config::ViewerLayout layout) {
  layout_ = layout;
  maximised_ = -1;
  // A PET/CT reader's MIP turns; back in the standard layout the 3D view stands still.
  setOrbit(petCtLayout() ? Orbit::Spin : Orbit::Off);
  markAllDirty();
}

namespace {

// The plane an MPR pane shows in `layout`: its slot's in the standard layout, the layout's own
// in PET/CT (the three MPR panes in step).
StandardView mprViewIn(config::ViewerLayout layout, int pane) {
  switch (layout) {
    case config::ViewerLayout::Standard:
      break;
    case config::ViewerLayout::PetCtAxial:
      return StandardView::Inferior;
    case config::ViewerLayout::PetCtCoronal:
      return StandardView::Anterior;
    case config::ViewerLayout::PetCtSagittal:
      return StandardView::Left;
  }
  return kMprViews[std::clamp(pane, 1, 3) - 1];
}

}  // namespace

StandardView ViewerState::mprView(int pane) const { return mprViewIn(layout_, pane); }

bool ViewerState::paneShowsFunctional(int pane) const {
  return pane == k3d && petCtLayout() && functional_ != nullptr;
}

std::string ViewerState::paneTitle(int pane) const {
  if (!petCtLayout()) return pane == k3d ? "3D" : kPaneNames[pane];
  const Volume& shown = functional_ ? *functional_ : anatomical_;
  const char* role = functional_ ? "functional" : "anatomical";
  switch (pane) {
    case k3d:
      return "MIP " + volumeName(shown, role);
    case kAxial:
      return volumeName(anatomical_, "anatomical");
    case kCoronal:
      return volumeName(shown, role);
    default:
      return "fused";
  }
}

int ViewerState::paneCell(int pane) const {
  if (!petCtLayout()) return pane;
  return pane == k3d ? 3 : pane - 1;  // anatomical, functional / fused, MIP
}

std::span<const RenderMode> ViewerState::modes3d() { return k3dModes; }

std::string ViewerState::volumeName(const Volume& v, const char* role) {
  return mvw::study::volumeName(v, role);
}

void ViewerState::markAllDirty() {
  for (auto& p : panes_) p.dirty = true;
}

void ViewerState::markMprDirty() {
  for (int p = kAxial; p < kPaneCount; ++p) markDirty(p);
}

bool ViewerState::anyDirty() const {
  return std::any_of(panes_.begin(), panes_.end(), [](const PaneState& p) { return p.dirty; });
}

void ViewerState::drag(int pane, double dx, double dy, MouseButton button, bool ctrl) {
  if (pane == k3d) {
    if (button == MouseButton::Left) {
      setOrbit(Orbit::Off);  // the reader takes the camera: the orbit stops where it is
      view3d_.camera.azimuthDeg += dx * 180.0;
      view3d_.camera.elevationDeg =
          std::clamp(view3d_.camera.elevationDeg + dy * 180.0, -89.0, 89.0);
    } else if (button == MouseButton::Right) {
      view3d_.camera.zoom = std::clamp(view3d_.camera.zoom * std::exp(-2.0 * dy), 0.1, 20.0);
    } else {
      // Pan by the pane's extent in mm: the dragged point stays under the mouse.
      const double mm = 2.0 * scene_.radius / view3d_.camera.zoom;
      view3d_.camera.panMm += glm::dvec2(-dx * mm, dy * mm);
    }
    markDirty(k3d);
    return;
  }
  if (button == MouseButton::Middle && !ctrl) {  // pan: the dragged point follows the mouse
    const render::Camera& cam = pane_(pane).camera;
    const double heightMm = 2.0 * cam.halfHeightMm;
    panPane(pane, dx * heightMm * cam.aspect, -dy * heightMm);
    return;
  }
  if (button == MouseButton::Right || ctrl) {  // window / level, as workstation viewers do
    const auto [lo, hi] = scene_.valueRange;
    mprWindow_.window = std::max(1e-3, mprWindow_.window * std::exp(dx * 2.0));
    mprWindow_.level -= dy * (hi - lo) * 0.5;
    markMprDirty();
    if (render::showsAnatomyOnCutFace(view3d_)) markDirty(k3d);  // its cut face follows
  }
}

glm::dvec3 ViewerState::onPlane(int pane, double x, double y) const {
  const render::Camera& cam = pane_(pane).camera;
  const glm::dvec3 origin = render::rayThrough(cam, {x * 2.0 - 1.0, 1.0 - y * 2.0}).origin;
  return origin + glm::dot(crosshair_ - origin, cam.forward) * cam.forward;
}

void ViewerState::click(int pane, double x, double y) {
  if (pane == k3d) return;
  crosshair_ = onPlane(pane, x, y);  // stays on this pane's plane
  markMprDirty();
}

void ViewerState::zoomPane(int pane, double factor) {
  if (!(factor > 0) || !std::isfinite(factor)) return;
  if (pane == k3d) {
    view3d_.camera.zoom = std::clamp(view3d_.camera.zoom * factor, 0.1, 20.0);
    markDirty(k3d);
    return;
  }
  mprZoom_ = std::clamp(mprZoom_ * factor, kMinMprZoom, kMaxMprZoom);
  markMprDirty();
}

void ViewerState::panPane(int pane, double rightMm, double upMm) {
  if (pane == k3d) {
    view3d_.camera.panMm += glm::dvec2(rightMm, upMm);
    markDirty(k3d);
    return;
  }
  render::CameraSettings plane;
  plane.view = mprView(pane);
  const render::Camera cam = render::makeCamera(plane, scene_.centre, scene_.radius, {64, 64});
  mprPan_ += cam.right * rightMm + cam.up * upMm;
  markMprDirty();
}

void ViewerState::mprFit() {
  mprZoom_ = 1.0;
  mprPan_ = glm::dvec3(0.0);
  markMprDirty();
}

void ViewerState::mprCentreOnCrosshair() {
  // Each pane's centre is scene centre minus the pan (in its plane): the crosshair there.
  mprPan_ = scene_.centre - crosshair_;
  markMprDirty();
}

std::string ViewerState::jumpNext() {
  if (!hottest_) {
    const Volume& v = functional_ ? *functional_ : anatomical_;
    const glm::ivec3 d = v.dimensions();
    double best = -std::numeric_limits<double>::infinity();
    glm::ivec3 at(0);
    for (int k = 0; k < d.z; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i)
          if (const double x = v.value(i, j, k); x > best) best = x, at = {i, j, k};
    hottest_ = v.worldFromIndexPoint(glm::dvec3(at));
    if (functional_)
      hottest_ = glm::dvec3(scene_.anatomicalFromFunctional * glm::dvec4(*hottest_, 1.0));
  }
  std::vector<std::pair<std::string, glm::dvec3>> places{{"the hottest voxel", *hottest_}};
  for (const auto& s : scene_.segmentCentres)
    places.push_back({"segment \"" + s.first + "\"", s.second});
  const auto& spheres = measurements_.all().spheres;
  for (std::size_t i = 0; i < spheres.size(); ++i)
    places.push_back({"ROI " + std::to_string(i + 1),
                      {spheres[i].centre[0], spheres[i].centre[1], spheres[i].centre[2]}});
  const std::size_t n = nextJump_++ % places.size();
  setCrosshair(places[n].second);
  mprCentreOnCrosshair();
  char buf[160];
  std::snprintf(buf, sizeof buf, "jump %zu/%zu: %s at %.1f, %.1f, %.1f mm LPS (J: next)", n + 1,
                places.size(), places[n].first.c_str(), places[n].second.x, places[n].second.y,
                places[n].second.z);
  requests_.setStatus(buf);
  return places[n].first;
}

void ViewerState::mprOneToOne() {
  // makeCamera fits the framing sphere's diameter in the shorter side, divided by the zoom.
  const glm::ivec2 size = glm::max(pane_(kAxial).size, glm::ivec2(8));
  const double shorter = std::min(size.x, size.y);
  mprZoom_ = std::clamp(2.0 * scene_.radius / (shorter * anatomical_.smallestSpacing()),
                        kMinMprZoom, kMaxMprZoom);
  markMprDirty();
}

void ViewerState::wheel(int pane, double steps, bool ctrl) {
  if (pane != k3d && ctrl) {
    zoomPane(pane, std::exp(0.1 * steps));
    return;
  }
  if (pane == k3d) {
    view3d_.camera.zoom = std::clamp(view3d_.camera.zoom * std::exp(0.1 * steps), 0.1, 20.0);
    markDirty(k3d);
    return;
  }
  // One notch: one slice of the finest spacing.
  crosshair_ += pane_(pane).camera.forward * steps * anatomical_.smallestSpacing();
  markMprDirty();
}

void ViewerState::key(char key, bool ctrl) {
  if (key >= '1' && key <= '5') {
    view3d_.mode = k3dModes[key - '1'];
  } else if (key == 'D') {
    view3d_.depthCue.on = !view3d_.depthCue.on;
    view3d_.depthCue.amount = view3d_.depthCue.on ? 0.66 : 0.0;
    view3d_.depthCue.contrast = view3d_.depthCue.on ? 0.33 : 1.0;
  } else if (key == 'G' && functional_) {
    view3d_.glyphs.on = !view3d_.glyphs.on;
  } else if (key == 'F') {
    // Said on the status line, not toggled: a fusion the image could not show.
    if (!functional_) return requests_.setStatus("colour fusion needs a functional volume");
    if (!render::takesFusion(view3d_.mode))
      return requests_.setStatus(toString(view3d_.mode) +
                                 " cannot fuse the functional volume: colour fusion is for "
                                 "composite, isosurface, mip, minip and average");
    view3d_.overlay.fusion = !view3d_.overlay.fusion;
  } else if (key == 'P') {
    const auto names = mvw::study::presetsFor(anatomical_);
    auto it = std::find(names.begin(), names.end(), presetName_);
    presetName_ = it == names.end() || it + 1 == names.end() ? names.front() : *(it + 1);
    view3d_.transfer = render::transferPreset(presetName_);
  } else if (key == 'R') {
    setOrbit(Orbit::Off);
    view3d_.camera = render::CameraSettings{};
    crosshair_ = scene_.centre;
    mprZoom_ = 1.0;
    mprPan_ = glm::dvec3(0.0);
  } else if (key == 'O') {
    toggleOrbit(Orbit::Spin);
  } else if (key == 'K') {
    toggleOrbit(Orbit::Rock);
  } else if (key == 'Z') {
    mprFit();
  } else if (key == 'C') {
    mprCentreOnCrosshair();
  } else if (key == 'J') {
    jumpNext();
  } else if (key == 'X') {
    mprOneToOne();
  } else if (key == 'L') {
    setLayout(static_cast<config::ViewerLayout>((static_cast<int>(layout_) + 1) % 4));
  } else if (key == 'S' && ctrl) {
    saveConfig("mvw-view-state.json");
  } else if (key == 'S') {
    requests_.requestScreenshot("mvw-screenshot.png");
  } else {
    return;
  }
  markAllDirty();
}

void ViewerState::setGlyphLabel(int label, config::LabelGlyphKind kind) {
  std::vector<render::LabelGlyph>& chosen = view3d_.glyphLabels;
  std::erase_if(chosen, [&](const render::LabelGlyph& g) { return g.label == label; });
  if (kind != config::LabelGlyphKind::None) {
    render::LabelGlyph g;
    g.label = label;
    g.kind = *config::glyphKindOf(kind);
    if (auto it = labelNames_.find(label); it != labelNames_.end()) g.name = it->second;
    chosen.insert(std::upper_bound(chosen.begin(), chosen.end(), g,
                                   [](const auto& a, const auto& b) { return a.label < b.label; }),
                  g);
  }
  markDirty(k3d);
}

void ViewerState::toggleMaximised(int pane) { maximised_ = maximised_ == pane ? -1 : pane; }

void ViewerState::setMode(RenderMode mode) {
  view3d_.mode = mode;
  markAllDirty();
}

void ViewerState::setPreset(const std::string& name) {
  presetName_ = name;
  view3d_.transfer = render::transferPreset(name);
  markAllDirty();
}

void ViewerState::setMprWindow(const WindowLevel& window) {
  mprWindow_ = window;
  markAllDirty();
}

void ViewerState::setColormap(ColorTarget target, ColorMap map) {
  auto table = [&](ColorMap none) {
    return map == none ? std::nullopt : std::optional<ColorTable>(mvw::study::colorTable(map));
  };
  if (target == ColorTarget::View3d) view3d_.imageColors = table(ColorMap::Grey);
  if (target == ColorTarget::Mpr) mprColors_ = table(ColorMap::Grey);
  if (target == ColorTarget::Overlay) view3d_.overlayColors = table(ColorMap::HotMetal);
  if (target == ColorTarget::Functional) functionalColors_ = mvw::study::colorTable(map);
  markAllDirty();
}

ColorMap ViewerState::colormap(ColorTarget target) const {
  switch (target) {
    case ColorTarget::View3d:
      return view3d_.imageColors ? view3d_.imageColors->map : ColorMap::Grey;
    case ColorTarget::Mpr:
      return mprColors_ ? mprColors_->map : ColorMap::Grey;
    case ColorTarget::Functional:
      return functionalColors_.map;
    case ColorTarget::Overlay:
      break;
  }
  return view3d_.overlayColors ? view3d_.overlayColors->map : ColorMap::HotMetal;
}

void ViewerState::advanceOrbit() {
  const std::optional<double> azimuth = orbit_.advance();
  if (!azimuth) return;
  view3d_.camera.azimuthDeg = *azimuth;
  markDirty(k3d);
}

void ViewerState::setPaneSize(int pane, glm::ivec2 size) {
  PaneState& p = pane_(pane);
  if (size == p.size) return;
  p.size = size, p.dirty = true;
  if (pane == k3d) fitGlyphSpacing();
}

void ViewerState::fitGlyphSpacing() {
  const glm::ivec2 size = pane_(k3d).size;
  if (!glyphScaleView_ || !functional_ || size.x < 8 || size.y < 8) return;
  if (glyphSpacingMm(view3d_) != glyphScaleSpacingMm_) {
    glyphScaleView_.reset();  // the panel chose a spacing: it stays
    return;
  }
  // The view as `mvw render` would plan it at the pane's size, its camera as now shown
  // (applyGlyphScale leaves a spacing the config gives, and a paper map, as they are).
  mvw::study::PlannedView v{*glyphScaleView_, view3d_, presetName_};
  v.settings.size = size;
  mvw::study::applyGlyphScale(v, anatomical_, *functional_);
  v.settings.size = view3d_.size;
  view3d_ = std::move(v.settings);
  glyphScaleSpacingMm_ = glyphSpacingMm(view3d_);
}

bool ViewerState::needsRender(int pane) const {
  const PaneState& p = pane_(pane);
  return p.dirty && p.size.x >= 8 && p.size.y >= 8;
}

void ViewerState::setFunctionalDisplayWindow(double low, double high) {
  functionalDisplay_ = {low, std::max(high, low + 1e-6 * std::abs(low) + 1e-12)};
  markAllDirty();
}

render::RenderSettings ViewerState::renderSettings(int pane, bool interacting) const {
  return settingsIn(layout_, pane, interacting);
}

render::RenderSettings ViewerState::settingsIn(config::ViewerLayout layout, int pane,
                                               bool interacting) const {
  const PaneState& image = pane_(pane);
  const bool petCt = layout != config::ViewerLayout::Standard;
  // The functional window (the overlay's, the PET/CT layout's functional pane and MIP).
  const auto [flo, fhi] = functionalDisplay_;
  render::RenderSettings s;
  if (pane == k3d && petCt) {
    // The rotating MIP of the functional volume (of the anatomical one where there is none),
    // in the functional colour map, turned by the 3D pane's camera (the orbit, the mouse).
    s.mode = RenderMode::Mip;
    s.camera = view3d_.camera;  // its zoom, pan and azimuth (the orbit), seen from the front
    s.camera.view = StandardView::Anterior;
    s.camera.elevationDeg = 0.0;
    s.camera.rollDeg = 0.0;
    s.camera.perspective = false;
    s.imageColors = functionalColors_;
    s.overlay.mpr = false;
    if (functional_)
      s.window = {fhi - flo, 0.5 * (flo + fhi)};
    else
      s.window = mprWindow_;
  } else if (pane == k3d) {
    s = view3d_;
    // The cut face shows the anatomy as the MPR panes do, under their window.
    if (render::showsAnatomyOnCutFace(s)) s.window = mprWindow_;
  } else {
    s.mode = RenderMode::Mpr;
    s.camera.view = mprViewIn(layout, pane);
    s.window = mprWindow_;
    s.overlay.opacity = view3d_.overlay.opacity;
    s.overlay.threshold = view3d_.overlay.threshold;
    s.functionalWindow = view3d_.functionalWindow;
    s.functionalClasses = view3d_.functionalClasses;
    s.imageColors = mprColors_;
    s.overlayColors = view3d_.overlayColors;
    s.segmentationOutlines = segmentOutlines_;
    s.camera.zoom = mprZoom_;
    const render::Camera plane =
        render::makeCamera(s.camera, scene_.centre, scene_.radius, glm::max(image.size, 1));
    s.camera.panMm = {glm::dot(mprPan_, plane.right), glm::dot(mprPan_, plane.up)};
    s.planeOffsetMm = glm::dot(crosshair_ - scene_.centre, plane.forward);
    if (petCt && pane == kAxial) s.overlay.mpr = false;  // the anatomy alone
    if (petCt && pane == kCoronal && functional_) {
      // The functional volume alone: every value inside its box in the functional colour map
      // at full opacity (the threshold below the window), over an anatomy drawn black.
      ColorTable black = greyTable(false);
      black.rgb.fill({0, 0, 0});
      s.imageColors = black;
      s.overlayColors = functionalColors_;
      s.overlay.opacity = 1.0f;
      s.overlay.threshold = -1.0f;
      s.functionalWindow = {flo, fhi};
    } else if (petCt && pane == kCoronal) {
      s.imageColors = functionalColors_;  // the one volume in the functional colour map
    }
  }
  s.size = image.size;
  if (pane == k3d && interacting) {  // coarse while dragging
    s.size = glm::max(image.size / dragDivisor_, glm::ivec2(8));
    s.stepMm = dragDivisor_ * anatomical_.smallestSpacing();
  }
  return s;
}

std::string ViewerState::caption(int pane, const render::RenderSettings& s) const {
  const auto [lo, hi] = scene_.valueRange;
  mvw::study::PlannedView shown{viewConfigOf(pane, layout_), s,
                                pane == k3d && !petCtLayout() ? presetName_ : ""};
  std::string text = mvw::study::viewCaption(shown, windowOrFullRange(s.window, lo, hi));
  // A PET without SUV says so, with why (study::noSuvNote), on every pane that shows it.
  const bool showsFunctional = render::showsFunctional(s, functional_ != nullptr);
  for (const Volume* v : {&anatomical_, showsFunctional ? functional_ : nullptr})
    if (const std::string note = v ? mvw::study::noSuvNote(*v) : ""; !note.empty())
      text += "  " + note;
  if (!petCtLayout()) return text;
  if (pane == kCoronal && functional_) {
    // The functional pane's window is the functional one (the anatomy's is drawn black).
    const auto [flo, fhi] = functionalDisplay_;
    char window[96];
    std::snprintf(window, sizeof window, "  %.4g-%.4g ", flo, fhi);
    const std::string& unit = functional_->metadata().unit;
    text = "mpr " + config::toString(shown.config.view) + window +
           (unit.empty() ? "(no unit)" : unit) + "  " + toString(functionalColors_.map);
    if (const std::string note = mvw::study::noSuvNote(*functional_); !note.empty())
      text += "  " + note;
  }
  return paneTitle(pane) + "  " + text;
}

render::GlyphLegend ViewerState::glyphLegend(int pane, const render::RenderSettings& s) const {
  if (!functional_) return {};
  mvw::study::PlannedView shown{viewConfigOf(pane, layout_), s, ""};
  return mvw::study::glyphLegend(shown, functional_->metadata().unit, scene_.functionalRange);
}

void ViewerState::rendered(int pane, const render::Camera& camera, Image raw, bool interacting,
                           double milliseconds) {
  PaneState& p = pane_(pane);
  if (interacting && pane == k3d) {
    if (milliseconds > kDragFrameBudgetMs)
      dragDivisor_ = std::min(dragDivisor_ + 1, kMaxDragDivisor);
    else if (milliseconds < kDragFrameBudgetMs / 3.0)
      dragDivisor_ = std::max(dragDivisor_ - 1, 2);
  }
  p.camera = camera;
  p.raw = std::move(raw);
  p.rendered = true;
  // Empty: every pixel the same (the background a ray that meets nothing leaves).
  p.empty = !p.raw.rgba.empty();
  for (std::size_t i = 4; i < p.raw.rgba.size() && p.empty; i += 4)
    p.empty = std::memcmp(p.raw.rgba.data(), p.raw.rgba.data() + i, 4) == 0;
  p.dirty = interacting && pane == k3d;  // refine when the drag ends
}

std::string ViewerState::emptyPaneMessage(int pane) const {
  const PaneState& p = pane_(pane);
  if (!p.rendered || !p.empty) return {};
  const auto [lo, hi] = scene_.valueRange;
  const std::string& unit = anatomical_.metadata().unit;
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4g .. %.4g", lo, hi);
  const std::string range = buf + (unit.empty() ? std::string(", no unit") : " " + unit);
  if (pane == k3d && view3d_.mode == RenderMode::Isosurface &&
      !(view3d_.iso > lo && view3d_.iso < hi)) {
    char iso[32];
    std::snprintf(iso, sizeof iso, "%g", view3d_.iso);
    return std::string("Nothing to show: the isovalue ") + iso +
           " lies outside the volume's values (" + range + "); set the iso value in the panel";
  }
  if (pane == k3d && view3d_.mode == RenderMode::Composite)
    return "Nothing to show: the preset " + presetName_ + " makes every value of " + range +
           " transparent; P: next preset";
  if (pane == k3d)
    return "Nothing to show with these settings (" + range + "); R resets the camera";
  return "Nothing to show: the plane or the window leaves the pane empty (" + range +
         "); Z fits the panes, R resets";
}

config::ViewConfig ViewerState::viewConfigOf(int pane, config::ViewerLayout layout) const {
  const bool petCt = layout != config::ViewerLayout::Standard;
  const render::RenderSettings s = settingsIn(layout, pane, false);
  config::ViewConfig v = mvw::study::describeView(
      s, std::string("view-") + (petCt ? kPetCtPaneNames : kPaneNames)[pane],
      pane == k3d && !petCt ? presetName_ : "");
  // Glyphs shown over the functional volume's full range (G on a view without a window): saved
  // as that range, or `mvw render` would give the glyph view its default window instead.
  if (pane == k3d && v.glyphs.on && !v.functionalWindow.set() && v.functionalClasses == 0)
    v.functionalWindow = {scene_.functionalRange.first, scene_.functionalRange.second};
  if (pane != k3d)  // axial, coronal, sagittal: the planes' own names
    v.view = s.camera.view == StandardView::Inferior   ? config::ViewName::Axial
             : s.camera.view == StandardView::Anterior ? config::ViewName::Coronal
                                                       : config::ViewName::Sagittal;
  return v;
}

void ViewerState::saveConfig(const std::filesystem::path& file) const {
  config::StudyConfig study = study_;
  if (study.name.empty()) study.name = "saved from mvw view";
  // A PACS series stays named by its server, study and series (the cache is not the source).
  if (study.anatomical.pacs.empty()) study.anatomical.path = anatomical_.metadata().sourcePath;
  if (functional_) {
    if (!study.functional) study.functional.emplace();
    if (study.functional->pacs.empty()) study.functional->path = functional_->metadata().sourcePath;
  }
  // The standard layout's four views (what `mvw render` can render of any layout's state: the
  // 3D view, and the three MPR planes at the MPR panes' zoom, pan and crosshair), and the
  // layout the viewer opens the state in.
  study.render.views.clear();
  for (int p = 0; p < kPaneCount; ++p)
    study.render.views.push_back(viewConfigOf(p, config::ViewerLayout::Standard));
  study.layout = layout_;
  study.measurements = measurements_.all();
  config::writeStudyConfig(study, file);
}

void ViewerState::dump(int pane, const std::filesystem::path& file) const {
  io::writePng(pane_(pane).raw, file);
}

std::optional<glm::dmat4> ViewerState::finishRegistration() {
  std::optional<RegistrationWorker::Outcome> outcome = registration_.finish();
  if (!outcome) return std::nullopt;
  if (!outcome->result) {
    requests_.setStatus("registration failed: " + outcome->error);
    return std::nullopt;
  }
  markAllDirty();
  scene_.anatomicalFromFunctional = outcome->result->transform.fixedFromMoving();
  measurements_.setPlacement(scene_.anatomicalFromFunctional);  // the functional ROIs move
  return scene_.anatomicalFromFunctional;
}

ViewerProbe ViewerState::probe(const glm::dvec3& world) const {
  ViewerProbe p;
  p.anatomical = sampleAt(anatomical_, world, &p.anatomicalInside);
  // The anatomical voxel's centre (the point itself outside the anatomy).
  const glm::dvec3 ijk =
      glm::dvec3(glm::inverse(anatomical_.worldFromIndex()) * glm::dvec4(world, 1.0));
  p.at = p.anatomicalInside ? anatomical_.worldFromIndexPoint(glm::round(ijk)) : world;
  if (functional_) {
    const glm::dvec3 f =
        glm::dvec3(glm::inverse(scene_.anatomicalFromFunctional) * glm::dvec4(p.at, 1.0));
    p.functional = sampleLinear(*functional_, f, &p.functionalInside);
  }
  return p;
}

std::string ViewerState::readout(const glm::dvec3& world) const {
  const ViewerProbe p = probe(world);
  // A PET without SUV: its value says so, and why (study::noSuvNote).
  const auto noSuv = [](const Volume& v) {
    const std::string note = mvw::study::noSuvNote(v);
    return note.empty() ? note : " (" + note + ")";
  };
  std::string text = volumeName(anatomical_, "anatomical") + " " +
                     (p.anatomicalInside ? formatValue(p.anatomical, anatomical_.metadata().unit) +
                                               noSuv(anatomical_)
                                         : std::string("outside"));
  if (functional_)
    text += " | " + volumeName(*functional_, "functional") + " " +
            (p.functionalInside
                 ? formatValue(p.functional, functional_->metadata().unit) + noSuv(*functional_)
                 : std::string("outside"));
  return text;
}

}  // namespace mvw::viewer
