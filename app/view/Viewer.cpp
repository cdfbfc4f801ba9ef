#include "Viewer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <thread>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <nlohmann/json.hpp>

#include "../FunctionalPlacement.h"
#include "../ViewPlan.h"
#include "GlfwContext.h"
#include "mvw/core/Error.h"
#include "mvw/io/PngWriter.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/resampling/RigidRegistration.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;
using render::RenderMode;
using render::StandardView;

enum Pane { k3d = 0, kAxial, kCoronal, kSagittal, kPaneCount };
const char* kPaneNames[kPaneCount] = {"3d", "axial", "coronal", "sagittal"};
const StandardView kMprViews[3] = {StandardView::Inferior, StandardView::Anterior, StandardView::Left};
const RenderMode k3dModes[] = {RenderMode::Composite, RenderMode::Isosurface, RenderMode::Mip, RenderMode::MinIp,
                               RenderMode::Average};
const char* kModeLabels[] = {"composite", "isosurface", "mip (depth cue: D)", "minip", "average"};

struct PaneImage {
  GLuint texture = 0;
  Image image;  // as shown, annotated
  Image raw;    // as rendered: what `mvw render --no-annotate` gives for the saved state
  render::Camera camera;
  bool dirty = true;
  glm::ivec2 size{0};
};

class Viewer {
 public:
  explicit Viewer(ViewerOptions o) : opt_(std::move(o)) {}
  int run();

 private:
  void setupRendering();
  void renderDirtyPanes(bool interacting);
  void drawUi();
  void drawPane(int pane, ImVec2 pos, ImVec2 size);
  void drawPanel();
  // Input, shared by the mouse/keyboard and the --script interpreter.
  void onDrag(int pane, double dx, double dy, int button, bool ctrl);
  void onClick(int pane, double x, double y);  // x, y: 0..1 across the pane
  void onWheel(int pane, double steps);
  void onKey(int key, bool ctrl);
  bool stepScript();
  void screenshot(const fs::path& file);
  void saveConfig(const fs::path& file) const;
  render::RenderSettings settingsOf(int pane) const;  // as rendered at the pane's size
  config::ViewConfig viewConfigOf(int pane) const;
  double sampleAt(const Volume& v, const glm::dvec3& world, bool* inside) const;
  void markAllDirty() {
    for (auto& p : panes_) p.dirty = true;
  }

  ViewerOptions opt_;
  std::unique_ptr<GlfwContext> context_;
  std::unique_ptr<render::VolumeRenderer> renderer_;
  std::array<PaneImage, kPaneCount> panes_;
  render::RenderSettings view3d_;
  std::string presetName_;
  double mprWindow_ = 0, mprLevel_ = 0;
  glm::dvec3 crosshair_{0.0};
  int maximised_ = -1;
  bool quit_ = false;
  std::vector<std::string> script_;
  std::size_t scriptLine_ = 0;
  int scriptWait_ = 0;
  std::string status_;
  int hoverPane_ = -1;
  glm::dvec3 hoverWorld_{0.0};
  bool hoverValid_ = false;
  bool dragging_ = false;
  std::string registration_ = "none";
  // Registration re-run from the panel, on a worker thread: the UI keeps drawing.
  std::thread registrationThread_;
  std::atomic<bool> registrationDone_{false};
  bool registering_ = false;
  std::chrono::steady_clock::time_point registrationStart_;
  resampling::RegistrationResult registrationResult_;
  std::string registrationError_;
  void startRegistration();
  void finishRegistration();
};

void Viewer::startRegistration() {
  if (registering_ || !opt_.functional) return;
  registering_ = true;
  registrationDone_ = false;
  registrationError_.clear();
  registrationStart_ = std::chrono::steady_clock::now();
  registrationThread_ = std::thread([this] {
    try {
      registrationResult_ = resampling::registerRigid(opt_.anatomical, *opt_.functional);
    } catch (const std::exception& e) {
      registrationError_ = e.what();
    }
    registrationDone_ = true;
  });
}

void Viewer::finishRegistration() {
  if (!registering_ || !registrationDone_) return;
  registrationThread_.join();
  registering_ = false;
  if (!registrationError_.empty()) {
    status_ = "registration failed: " + registrationError_;
    return;
  }
  renderer_->setFunctional(*opt_.functional, registrationResult_.transform.fixedFromMoving());
  registration_ = "rigid (re-run), MI " + std::to_string(registrationResult_.levels.empty() ? 0.0
                                                            : registrationResult_.levels.back().metricEnd) +
                  (registrationResult_.converged ? ", converged" : ", NOT converged") + ", " +
                  std::to_string(registrationResult_.seconds).substr(0, 4) + " s";
  markAllDirty();
}

std::vector<std::string> presetNames() { return render::transferPresetNames(); }

void Viewer::setupRendering() {
  renderer_ = std::make_unique<render::VolumeRenderer>(*context_, opt_.anatomical);
  if (opt_.functional) {
    const FunctionalPlacement placement = placeFunctional(opt_.study, opt_.anatomical, *opt_.functional);
    renderer_->setFunctional(*opt_.functional, placement.anatomicalFromFunctional);
    registration_ = opt_.study.registration.method;
    if (placement.report.contains("mutual_information"))
      registration_ += ", MI " + std::to_string(placement.report["mutual_information"].get<double>());
  }
  const auto [lo, hi] = renderer_->valueRange();
  const bool ct = opt_.anatomical.metadata().modality == "CT" || opt_.anatomical.metadata().unit == "HU";
  presetName_ = ct ? "ct-bone" : "mr-default";
  view3d_.transfer = render::transferPreset(presetName_);
  view3d_.camera.view = StandardView::Anterior;
  view3d_.isoValue = ct ? 300.0 : lo + 0.4 * (hi - lo);
  mprWindow_ = ct ? 400.0 : hi - lo;
  mprLevel_ = ct ? 40.0 : 0.5 * (lo + hi);
  crosshair_ = renderer_->centre();
  // The study's first view the 3D pane can show sets it up, exactly as `mvw render` would
  // render it (glyphs, attribute window, crop, light, ...); an MPR view sets the MPR panes'
  // window and the overlay.
  std::vector<PlannedView> planned = planViews(opt_.study);
  for (PlannedView& v : planned) {
    if (std::find(std::begin(k3dModes), std::end(k3dModes), v.settings.mode) == std::end(k3dModes)) continue;
    applyDefaultPreset(v, opt_.anatomical);
    view3d_ = v.settings;
    presetName_ = v.presetName;
    break;
  }
  for (const PlannedView& v : planned)
    if (v.settings.mode == RenderMode::Mpr) {
      if (v.settings.window > 0) mprWindow_ = v.settings.window, mprLevel_ = v.settings.level;
      break;
    }
}

render::RenderSettings Viewer::settingsOf(int pane) const {
  const PaneImage& image = panes_[static_cast<std::size_t>(pane)];
  render::RenderSettings s;
  if (pane == k3d) {
    s = view3d_;
  } else {
    s.mode = RenderMode::Mpr;
    s.camera.view = kMprViews[pane - 1];
    s.window = mprWindow_;
    s.level = mprLevel_;
    s.overlayOpacity = view3d_.overlayOpacity;
    s.overlayThreshold = view3d_.overlayThreshold;
    s.functionalLow = view3d_.functionalLow;
    s.functionalHigh = view3d_.functionalHigh;
    s.functionalClasses = view3d_.functionalClasses;
    const glm::dvec3 forward = render::makeCamera(s.camera, renderer_->centre(), renderer_->radius(), image.size).forward;
    s.planeOffsetMm = glm::dot(crosshair_ - renderer_->centre(), forward);
  }
  s.size = image.size;
  return s;
}

config::ViewConfig Viewer::viewConfigOf(int pane) const {
  config::ViewConfig v =
      describeView(settingsOf(pane), std::string("view-") + kPaneNames[pane], pane == k3d ? presetName_ : "");
  if (pane != k3d) v.view = kPaneNames[pane];  // axial, coronal, sagittal: the planes' own names
  return v;
}

void Viewer::renderDirtyPanes(bool interacting) {
  for (int p = 0; p < kPaneCount; ++p) {
    PaneImage& pane = panes_[static_cast<std::size_t>(p)];
    if (!pane.dirty || pane.size.x < 8 || pane.size.y < 8) continue;
    render::RenderSettings s = settingsOf(p);
    if (p == k3d && interacting) {  // coarse while dragging
      s.size = glm::max(pane.size / 2, glm::ivec2(8));
      s.stepMm = 2.0 * std::min({opt_.anatomical.spacing().x, opt_.anatomical.spacing().y, opt_.anatomical.spacing().z});
    }
    render::Frame f = renderer_->render(s);
    const auto [lo, hi] = renderer_->valueRange();
    std::string caption = p == k3d ? render::toString(s.mode) : std::string(kPaneNames[p]);
    if (p != k3d || s.mode != RenderMode::Composite) {
      char wl[64];
      std::snprintf(wl, sizeof wl, "  W %.0f L %.0f", s.window > 0 ? s.window : hi - lo,
                    s.window > 0 ? s.level : 0.5 * (hi + lo));
      caption += wl;
    } else {
      caption += "  " + presetName_;
    }
    pane.raw = f.image;
    render::annotate(f.image, f.camera, caption);
    pane.image = std::move(f.image);
    pane.camera = f.camera;
    if (!pane.texture) glGenTextures(1, &pane.texture);
    glBindTexture(GL_TEXTURE_2D, pane.texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, pane.image.width, pane.image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 pane.image.rgba.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    pane.dirty = interacting && p == k3d;  // refine when the drag ends
  }
}

double Viewer::sampleAt(const Volume& v, const glm::dvec3& world, bool* inside) const {
  const glm::dvec3 ijk = glm::dvec3(glm::inverse(v.worldFromIndex()) * glm::dvec4(world, 1.0));
  const glm::ivec3 n(std::lround(ijk.x), std::lround(ijk.y), std::lround(ijk.z));
  *inside = glm::all(glm::greaterThanEqual(n, glm::ivec3(0))) && glm::all(glm::lessThan(n, v.dimensions()));
  return *inside ? v.value(n.x, n.y, n.z) : 0.0;
}

void Viewer::onDrag(int pane, double dx, double dy, int button, bool ctrl) {
  if (pane == k3d) {
    if (button == 0) {
      view3d_.camera.azimuthDeg += dx * 180.0;
      view3d_.camera.elevationDeg = std::clamp(view3d_.camera.elevationDeg + dy * 180.0, -89.0, 89.0);
    } else if (button == 1) {
      view3d_.camera.zoom = std::clamp(view3d_.camera.zoom * std::exp(-2.0 * dy), 0.1, 20.0);
    } else {
      const double mm = 2.0 * renderer_->radius() / view3d_.camera.zoom;
      view3d_.camera.panMm += glm::dvec2(-dx * mm, dy * mm);
    }
    panes_[k3d].dirty = true;
    return;
  }
  if (button == 1 || ctrl) {  // window / level, as workstation viewers do
    const auto [lo, hi] = renderer_->valueRange();
    mprWindow_ = std::max(1e-3, mprWindow_ * std::exp(dx * 2.0));
    mprLevel_ -= dy * (hi - lo) * 0.5;
    for (int p = kAxial; p < kPaneCount; ++p) panes_[static_cast<std::size_t>(p)].dirty = true;
  }
}

void Viewer::onClick(int pane, double x, double y) {
  if (pane == k3d) return;
  const render::Camera& cam = panes_[static_cast<std::size_t>(pane)].camera;
  const glm::dvec3 origin = render::rayThrough(cam, {x * 2.0 - 1.0, 1.0 - y * 2.0}).origin;
  const double along = glm::dot(crosshair_ - origin, cam.forward);  // stay on this pane's plane
  crosshair_ = origin + along * cam.forward;
  for (int p = kAxial; p < kPaneCount; ++p) panes_[static_cast<std::size_t>(p)].dirty = true;
}

void Viewer::onWheel(int pane, double steps) {
  if (pane == k3d) {
    view3d_.camera.zoom = std::clamp(view3d_.camera.zoom * std::exp(0.1 * steps), 0.1, 20.0);
    panes_[k3d].dirty = true;
    return;
  }
  const glm::dvec3 s = opt_.anatomical.spacing();
  crosshair_ += panes_[static_cast<std::size_t>(pane)].camera.forward * steps * std::min({s.x, s.y, s.z});
  for (int p = kAxial; p < kPaneCount; ++p) panes_[static_cast<std::size_t>(p)].dirty = true;
}

void Viewer::onKey(int key, bool ctrl) {
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_5) view3d_.mode = k3dModes[key - GLFW_KEY_1];
  else if (key == GLFW_KEY_D) view3d_.depthCue = !view3d_.depthCue, view3d_.cueAmount = view3d_.depthCue ? 0.66 : 0.0,
                              view3d_.cueContrast = view3d_.depthCue ? 0.33 : 1.0;
  else if (key == GLFW_KEY_G && opt_.functional) view3d_.glyphs = !view3d_.glyphs;
  else if (key == GLFW_KEY_F && opt_.functional) view3d_.fusion = !view3d_.fusion;
  else if (key == GLFW_KEY_P) {
    const auto names = presetNames();
    auto it = std::find(names.begin(), names.end(), presetName_);
    presetName_ = it == names.end() || it + 1 == names.end() ? names.front() : *(it + 1);
    view3d_.transfer = render::transferPreset(presetName_);
  } else if (key == GLFW_KEY_R) {
    view3d_.camera = render::CameraSettings{};
    crosshair_ = renderer_->centre();
  } else if (key == GLFW_KEY_S && ctrl) {
    saveConfig("mvw-view-state.json");
  } else if (key == GLFW_KEY_S) {
    screenshot("mvw-screenshot.png");
  } else {
    return;
  }
  markAllDirty();
}

void Viewer::screenshot(const fs::path& file) {
  const glm::ivec2 size = context_->size();
  Image img(size.x, size.y);
  std::vector<std::uint8_t> rows(img.rgba.size());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  const std::size_t row = static_cast<std::size_t>(size.x) * 4;
  for (int y = 0; y < size.y; ++y) std::copy_n(rows.data() + (size.y - 1 - y) * row, row, img.rgba.data() + y * row);
  io::writePng(img, file);
  status_ = "saved " + file.string();
}

void Viewer::saveConfig(const fs::path& file) const {
  config::StudyConfig study = opt_.study;
  if (study.name.empty()) study.name = "saved from mvw view";
  study.anatomical.path = opt_.anatomical.metadata().sourcePath;
  if (opt_.functional) {
    if (!study.functional) study.functional.emplace();
    study.functional->path = opt_.functional->metadata().sourcePath;
  }
  study.render.views.clear();
  for (int p = 0; p < kPaneCount; ++p) study.render.views.push_back(viewConfigOf(p));
  config::writeStudyConfig(study, file);
}

// Script lines (for tests under Xvfb): key K [ctrl] | drag PANE dx dy [left|right|middle] |
// click PANE x y | wheel PANE n | wait FRAMES | screenshot FILE | save-config FILE |
// dump PANE FILE (the pane's full-resolution render, without annotations) | register (re-run
// the registration in the background) | wait-registration | quit. PANE: 3d, axial, coronal,
// sagittal; coordinates are fractions of the pane.
bool Viewer::stepScript() {
  if (scriptWait_ > 0) {
    --scriptWait_;
    return true;
  }
  if (scriptLine_ >= script_.size()) return false;
  std::istringstream in(script_[scriptLine_++]);
  std::string cmd;
  in >> cmd;
  auto paneOf = [&](const std::string& name) {
    for (int p = 0; p < kPaneCount; ++p)
      if (name == kPaneNames[p]) return p;
    throw InputError(opt_.script, "unknown pane '" + name + "'");
  };
  if (cmd.empty() || cmd[0] == '#') return true;
  if (cmd == "key") {
    std::string k, mod;
    in >> k >> mod;
    const int key = k.size() == 1 ? std::toupper(static_cast<unsigned char>(k[0])) : -1;
    onKey(key, mod == "ctrl");
  } else if (cmd == "drag") {
    std::string pane, button;
    double dx = 0, dy = 0;
    in >> pane >> dx >> dy >> button;
    onDrag(paneOf(pane), dx, dy, button == "right" ? 1 : button == "middle" ? 2 : 0, false);
  } else if (cmd == "click") {
    std::string pane;
    double x = 0, y = 0;
    in >> pane >> x >> y;
    onClick(paneOf(pane), x, y);
  } else if (cmd == "wheel") {
    std::string pane;
    double n = 0;
    in >> pane >> n;
    onWheel(paneOf(pane), n);
  } else if (cmd == "wait") {
    in >> scriptWait_;
  } else if (cmd == "screenshot" || cmd == "save-config" || cmd == "dump") {
    std::string a, b;
    in >> a >> b;
    if (cmd == "screenshot") screenshot(a);
    else if (cmd == "save-config") saveConfig(a);
    else io::writePng(panes_[static_cast<std::size_t>(paneOf(a))].raw, b);
  } else if (cmd == "register") {
    startRegistration();
  } else if (cmd == "wait-registration") {
    if (registering_) --scriptLine_;  // stay on this line until the worker is done
  } else if (cmd == "quit") {
    quit_ = true;
  } else {
    throw InputError(opt_.script, "line " + std::to_string(scriptLine_) + ": unknown command '" + cmd + "'");
  }
  return true;
}

void Viewer::drawPane(int pane, ImVec2 pos, ImVec2 size) {
  PaneImage& p = panes_[static_cast<std::size_t>(pane)];
  const glm::ivec2 want(std::max(8, static_cast<int>(size.x)), std::max(8, static_cast<int>(size.y)));
  if (want != p.size) p.size = want, p.dirty = true;
  ImGui::SetCursorScreenPos(pos);
  ImGui::PushID(pane);
  ImGui::InvisibleButton("pane", size, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                                           ImGuiButtonFlags_MouseButtonMiddle);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  if (p.texture)
    draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(p.texture)), pos,
                   ImVec2(pos.x + size.x, pos.y + size.y));
  ImGuiIO& io = ImGui::GetIO();
  const ImVec2 mouse = io.MousePos;
  const double fx = (mouse.x - pos.x) / size.x, fy = (mouse.y - pos.y) / size.y;
  if (ImGui::IsItemHovered()) {
    hoverPane_ = pane;
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) maximised_ = maximised_ == pane ? -1 : pane;
    if (io.MouseWheel != 0.0f) onWheel(pane, io.MouseWheel);
    if (pane != k3d && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && !io.KeyCtrl) onClick(pane, fx, fy);
    if (pane != k3d) {
      const glm::dvec3 origin = render::rayThrough(p.camera, {fx * 2 - 1, 1 - fy * 2}).origin;
      hoverWorld_ = origin + glm::dot(crosshair_ - origin, p.camera.forward) * p.camera.forward;
      hoverValid_ = true;
    }
  }
  for (int b = 0; b < 3; ++b)
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(b, 0.0f)) {
      const ImVec2 d = io.MouseDelta;
      if (d.x != 0 || d.y != 0) {
        if (pane != k3d && b == 0 && !io.KeyCtrl) onClick(pane, fx, fy);
        else onDrag(pane, d.x / size.x, d.y / size.y, b, io.KeyCtrl);
        dragging_ = true;
      }
    }
  if (pane != k3d && p.texture) {  // the linked crosshair
    const glm::dvec4 c = p.camera.clipFromWorld * glm::dvec4(crosshair_, 1.0);
    const float cx = pos.x + static_cast<float>((c.x / c.w + 1) * 0.5) * size.x;
    const float cy = pos.y + static_cast<float>((1 - c.y / c.w) * 0.5) * size.y;
    draw->AddLine(ImVec2(cx, pos.y), ImVec2(cx, pos.y + size.y), IM_COL32(80, 200, 255, 160));
    draw->AddLine(ImVec2(pos.x, cy), ImVec2(pos.x + size.x, cy), IM_COL32(80, 200, 255, 160));
  }
  ImGui::PopID();
}

void Viewer::drawPanel() {
  ImGui::Text("%s", opt_.study.name.empty() ? "mvw view" : opt_.study.name.c_str());
  ImGui::Separator();
  int mode = 0;
  for (int i = 0; i < 5; ++i)
    if (k3dModes[i] == view3d_.mode) mode = i;
  if (ImGui::Combo("3D mode", &mode, kModeLabels, 5)) view3d_.mode = k3dModes[mode], markAllDirty();
  const auto names = presetNames();
  if (ImGui::BeginCombo("preset", presetName_.c_str())) {
    for (const auto& n : names)
      if (ImGui::Selectable(n.c_str(), n == presetName_)) {
        presetName_ = n;
        view3d_.transfer = render::transferPreset(n);
        markAllDirty();
      }
    ImGui::EndCombo();
  }
  // Transfer function points: opacity per point.
  if (ImGui::TreeNode("transfer function points")) {
    for (std::size_t i = 0; i < view3d_.transfer.points.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      auto& pt = view3d_.transfer.points[i];
      float value = static_cast<float>(pt.value);
      if (ImGui::DragFloat("value", &value, 1.0f)) pt.value = value, panes_[k3d].dirty = true;
      if (ImGui::SliderFloat("opacity", &pt.rgba.a, 0.0f, 1.0f)) panes_[k3d].dirty = true;
      if (ImGui::ColorEdit3("colour", &pt.rgba.r)) panes_[k3d].dirty = true;
      ImGui::PopID();
    }
    ImGui::TreePop();
  }
  // Sampling quality: the ray step in mm (0 = half the smallest voxel spacing).
  float step = static_cast<float>(view3d_.stepMm);
  if (ImGui::SliderFloat("step mm (0 auto)", &step, 0.0f, 4.0f)) view3d_.stepMm = step, panes_[k3d].dirty = true;
  float iso = static_cast<float>(view3d_.isoValue);
  const auto [lo, hi] = renderer_->valueRange();
  if (ImGui::SliderFloat("iso value", &iso, float(lo), float(hi))) view3d_.isoValue = iso, panes_[k3d].dirty = true;
  float w = static_cast<float>(mprWindow_), l = static_cast<float>(mprLevel_);
  if (ImGui::DragFloat("MPR window", &w, 2.0f, 1.0f, float(hi - lo) * 2) |
      ImGui::DragFloat("MPR level", &l, 2.0f, float(lo), float(hi))) {
    mprWindow_ = w, mprLevel_ = l;
    markAllDirty();
  }
  ImGui::Separator();
  ImGui::Text("depth-cued MIP (Heidrich 1995)");
  bool cue = view3d_.depthCue;
  if (ImGui::Checkbox("depth cue", &cue)) view3d_.depthCue = cue, panes_[k3d].dirty = true;
  float b0 = float(view3d_.cueBrightness), a = float(view3d_.cueAmount), b = float(view3d_.cueContrast);
  if (ImGui::SliderFloat("brightness", &b0, 0, 1) | ImGui::SliderFloat("depth cue", &a, 0, 1) |
      ImGui::SliderFloat("contrast", &b, 0, 1)) {
    view3d_.cueBrightness = b0, view3d_.cueAmount = a, view3d_.cueContrast = b;
    panes_[k3d].dirty = true;
  }
  if (opt_.functional) {
    ImGui::Separator();
    ImGui::Text("functional volume");
    if (ImGui::SliderFloat("overlay opacity", &view3d_.overlayOpacity, 0, 1) |
        ImGui::SliderFloat("threshold", &view3d_.overlayThreshold, 0, 1))
      markAllDirty();
    // The attribute's mapping to 0..1 (colour map, glyph beta): a window, or label classes.
    const auto [flo, fhi] = renderer_->functionalRange();
    const bool userWindow = view3d_.functionalHigh > view3d_.functionalLow;
    float fw[2] = {float(userWindow ? view3d_.functionalLow : flo), float(userWindow ? view3d_.functionalHigh : fhi)};
    if (ImGui::DragFloatRange2("attribute", &fw[0], &fw[1], float(fhi - flo) / 200.0f, float(flo), float(fhi))) {
      view3d_.functionalLow = fw[0];
      view3d_.functionalHigh = std::max(double(fw[1]), double(fw[0]) + 1e-6 * (fhi - flo));
      markAllDirty();
    }
    int classes = view3d_.functionalClasses;
    if (ImGui::InputInt("classes", &classes)) {
      view3d_.functionalClasses = std::clamp(classes, 0, 64);
      markAllDirty();
    }
    bool glyphs = view3d_.glyphs, fusion = view3d_.fusion;
    if (ImGui::Checkbox("glyphs (G)", &glyphs)) view3d_.glyphs = glyphs, panes_[k3d].dirty = true;
    ImGui::SameLine();
    if (ImGui::Checkbox("colour fusion (F)", &fusion)) view3d_.fusion = fusion, panes_[k3d].dirty = true;
    float gd = float(view3d_.glyphDiameterMm);
    if (ImGui::SliderFloat("glyph size mm", &gd, 1, 40)) view3d_.glyphDiameterMm = gd, panes_[k3d].dirty = true;
    int method = view3d_.glyphSizeControl ? 0 : 1;
    const char* methods[] = {"sized (eqs. 2-3)", "simple (eq. 1)"};
    if (ImGui::Combo("glyph method", &method, methods, 2)) view3d_.glyphSizeControl = method == 0, panes_[k3d].dirty = true;
    const char* convexity[] = {"convex", "concave", "both"};
    int convexityIndex = static_cast<int>(view3d_.glyphConvexity);  // the enum's order
    if (ImGui::Combo("bumps", &convexityIndex, convexity, 3)) {
      view3d_.glyphConvexity = static_cast<render::GlyphConvexity>(convexityIndex);
      panes_[k3d].dirty = true;
    }
    ImGui::TextWrapped("registration: %s", registration_ == "none" ? "none (world coordinates)" : registration_.c_str());
    if (registering_) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - registrationStart_).count();
      ImGui::Text("registering (mutual information)... %.1f s", s);
    } else if (ImGui::Button("re-run registration (rigid MI)")) {
      startRegistration();
    }
  }
  ImGui::Separator();
  ImGui::Text("crosshair %.1f, %.1f, %.1f mm (LPS)", crosshair_.x, crosshair_.y, crosshair_.z);
  if (hoverValid_) {
    bool inside = false;
    const double v = sampleAt(opt_.anatomical, hoverWorld_, &inside);
    ImGui::Text("cursor %.1f, %.1f, %.1f: %s", hoverWorld_.x, hoverWorld_.y, hoverWorld_.z,
                inside ? (std::to_string(static_cast<long long>(std::lround(v))) + " " + opt_.anatomical.metadata().unit).c_str()
                       : "outside");
    if (opt_.functional) {
      bool fin = false;
      const double fv = sampleAt(*opt_.functional, hoverWorld_, &fin);
      if (fin) ImGui::Text("functional %.4g %s", fv, opt_.functional->metadata().unit.c_str());
    }
  }
  ImGui::Separator();
  ImGui::TextWrapped("Mouse: 3D left-drag rotate, right-drag zoom, middle-drag pan, wheel zoom. MPR: left "
                     "click/drag moves the crosshair, wheel scrolls slices, right-drag or Ctrl-drag window/level. "
                     "Double-click maximises a view.\nKeys: 1-5 modes, D depth cue, G glyphs, F fusion, P next "
                     "preset, R reset, S screenshot, Ctrl+S save state as a study config.");
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
}

void Viewer::drawUi() {
  ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(io.DisplaySize);
  ImGui::Begin("mvw", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse);
  const float panel = 340.0f;
  ImGui::BeginChild("panel", ImVec2(panel, 0), true);
  drawPanel();
  ImGui::EndChild();
  const ImVec2 origin(panel + 12.0f, 8.0f);
  const ImVec2 area(io.DisplaySize.x - origin.x - 8.0f, io.DisplaySize.y - 16.0f);
  hoverValid_ = false;
  if (maximised_ >= 0) {
    drawPane(maximised_, origin, area);
  } else {
    const ImVec2 cell(area.x / 2 - 2, area.y / 2 - 2);
    for (int p = 0; p < kPaneCount; ++p)
      drawPane(p, ImVec2(origin.x + (p % 2) * (cell.x + 4), origin.y + (p / 2) * (cell.y + 4)), cell);
  }
  ImGui::End();
  if (!io.WantTextInput) {
    const bool ctrl = io.KeyCtrl;
    for (int key : {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5, GLFW_KEY_D, GLFW_KEY_G, GLFW_KEY_F,
                    GLFW_KEY_P, GLFW_KEY_R, GLFW_KEY_S})
      if (ImGui::IsKeyPressed(key, false)) onKey(key, ctrl);
  }
}

int Viewer::run() {
  if (!opt_.script.empty()) {
    std::ifstream in(opt_.script);
    if (!in) throw InputError(opt_.script, "cannot read the script");
    for (std::string line; std::getline(in, line);) script_.push_back(line);
  }
  context_ = std::make_unique<GlfwContext>(glm::ivec2(opt_.width, opt_.height), "mvw view");
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(context_->window(), true);
  ImGui_ImplOpenGL3_Init("#version 450");
  setupRendering();
  int frames = 0;
  while (!glfwWindowShouldClose(context_->window()) && !quit_) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    dragging_ = false;
    finishRegistration();
    drawUi();
    renderDirtyPanes(dragging_);
    ImGui::Render();
    const glm::ivec2 fb = context_->size();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb.x, fb.y);
    glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    // Scripts act on a frame that is fully drawn (screenshots read the back buffer).
    if (!script_.empty() && frames > 1 && !stepScript()) quit_ = true;
    glfwSwapBuffers(context_->window());
    ++frames;
    bool anyDirty = false;
    for (const auto& p : panes_) anyDirty |= p.dirty;
    if (!anyDirty && script_.empty() && !registering_) glfwWaitEventsTimeout(0.05);  // idle: no busy loop
  }
  if (registrationThread_.joinable()) registrationThread_.join();
  for (auto& p : panes_)
    if (p.texture) glDeleteTextures(1, &p.texture);
  renderer_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return 0;
}

}  // namespace

int runViewer(ViewerOptions options) { return Viewer(std::move(options)).run(); }

}  // namespace mvw::app
