#pragma once
// What `mvw view` shows and how input changes it, without a window or GL: the four panes
// (3D and the axial, coronal and sagittal MPR), the 3D mode and preset, the linked
// crosshair, the MPR window/level, the camera maths of dragging, clicking and the wheel, the
// saved state, and the background registration. The mouse, the keyboard, the panel and the
// --script interpreter all act through this class; the window loop renders what it asks for.
#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

#include "RegistrationWorker.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Camera.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::app {

enum Pane { k3d = 0, kAxial, kCoronal, kSagittal, kPaneCount };
enum class MouseButton { Left = 0, Right = 1, Middle = 2 };
// The rotating 3D view: off, a full turn (spin) or back and forth (rock), about the patient's
// long axis as `mvw render --orbit` turns.
enum class Orbit { Off, Spin, Rock };
// Which image a colour map chooser sets: the 3D pane's projection, the MPR panes' anatomy, or
// the functional overlay (MPR) and fusion (3D).
enum class ColorTarget { View3d, Mpr, Overlay };

// What the renderer knows about the volumes that the state's maths need (the renderer holds
// them in GL; a test gives them by hand).
struct ViewerScene {
  glm::dvec3 centre{0.0};  // the sphere the cameras frame
  double radius = 1.0;
  std::pair<double, double> valueRange{0.0, 1.0};
  std::pair<double, double> functionalRange{0.0, 1.0};
  std::string registration = "none";  // how the functional volume was placed, for the panel
};

// The volumes' values under a world point (the panel's cursor readout).
struct ViewerProbe {
  bool anatomicalInside = false, functionalInside = false;
  double anatomical = 0.0, functional = 0.0;
};

class ViewerState {
 public:
  // The 3D pane opens on the study's first 3D view as `mvw render` would render it; the MPR
  // panes take the first MPR view's window. The study and the volumes must outlive the state
  // (a running registration reads them).
  ViewerState(const config::StudyConfig& study, const Volume& anatomical, const Volume* functional,
              ViewerScene scene);
  ~ViewerState() = default;  // a running registration is waited for, never abandoned
  ViewerState(const ViewerState&) = delete;
  ViewerState& operator=(const ViewerState&) = delete;

  static const char* paneName(int pane);                         // 3d, axial, coronal, sagittal
  static std::optional<int> paneNamed(const std::string& name);  // the inverse
  // The panel's line for the study's placement (placeFunctional's report).
  static std::string describePlacement(const std::string& method, const nlohmann::json& report);
  // The 3D pane's modes, in the order of the keys 1-5.
  static std::span<const render::RenderMode> modes3d();

  // Input. Drags and clicks are in fractions of the pane (y down); steps are wheel notches.
  void drag(int pane, double dx, double dy, MouseButton button, bool ctrl);
  void click(int pane, double x, double y);
  void wheel(int pane, double steps);
  // key: an upper-case letter or digit ('1'..'5' modes, 'D', 'G', 'F', 'P', 'R', 'S', 'O' spin,
  // 'K' rock); other keys do nothing.
  void key(char key, bool ctrl);
  void toggleMaximised(int pane);
  void setMode(render::RenderMode mode);  // one of modes3d()
  void setPreset(const std::string& name);
  void setMprWindow(double window, double level);
  // Colour maps (grey for the images and hot metal for the overlay are the defaults); the 3D
  // pane's shows in MIP, MinIP and average.
  void setColormap(ColorTarget target, ColorMap map);
  ColorMap colormap(ColorTarget target) const;

  // The rotating 3D view: spin turns 360 degrees in kOrbitFrames frames, rock swings +-30
  // degrees about the azimuth it started from; switching it off stops at the angle shown (so
  // a reader can stop where a finding shows best). The same toggle again switches it off.
  static constexpr int kOrbitFrames = 90;
  static constexpr double kRockRangeDeg = 30.0;
  void setOrbit(Orbit orbit);
  void toggleOrbit(Orbit orbit) { setOrbit(orbit_ == orbit ? Orbit::Off : orbit); }
  Orbit orbit() const { return orbit_; }
  // The window calls this once per drawn frame: the next step of the orbit (the 3D pane dirty).
  void advanceOrbit();

  // Rendering: the window loop sets each pane's size, renders the panes that need it with
  // renderSettings(), and reports each frame back.
  void setPaneSize(int pane, glm::ivec2 size);  // marks the pane dirty when it changes
  // Where the panel drew the pane this frame (window pixels, top left; size: setPaneSize).
  void setPaneOrigin(int pane, glm::ivec2 topLeft) { pane_(pane).origin = topLeft; }
  glm::ivec2 paneOrigin(int pane) const { return pane_(pane).origin; }
  glm::ivec2 paneSize(int pane) const { return pane_(pane).size; }
  bool needsRender(int pane) const;
  // As rendered at the pane's size; while interacting the 3D pane renders coarse.
  render::RenderSettings renderSettings(int pane, bool interacting = false) const;
  std::string caption(int pane, const render::RenderSettings& settings) const;
  // What the pane's glyphs mean (empty without glyphs), as `mvw render` burns it in.
  render::GlyphLegend glyphLegend(int pane, const render::RenderSettings& settings) const;
  void rendered(int pane, const render::Camera& camera, Image raw, bool interacting);
  bool anyDirty() const;
  void markDirty(int pane) { panes_[static_cast<std::size_t>(pane)].dirty = true; }
  void markAllDirty();

  // Files.
  void saveConfig(const std::filesystem::path& file) const;      // every pane as a study view
  void dump(int pane, const std::filesystem::path& file) const;  // the pane as rendered, raw
  // A screenshot is taken by the window once the frame is fully drawn.
  void requestScreenshot(std::filesystem::path file) { screenshot_ = std::move(file); }
  std::optional<std::filesystem::path> takeScreenshotRequest();
  // The pane as the window shows it (its rectangle of the framebuffer: the render with its
  // annotations, and the crosshair on an MPR pane), taken as the whole-window screenshot is.
  void requestPaneScreenshot(int pane, std::filesystem::path file) {
    paneScreenshot_ = {pane, std::move(file)};
  }
  std::optional<std::pair<int, std::filesystem::path>> takePaneScreenshotRequest() {
    return std::exchange(paneScreenshot_, std::nullopt);
  }
  void requestQuit() { quit_ = true; }
  bool quitRequested() const { return quit_; }
  void setStatus(std::string status) { status_ = std::move(status); }
  const std::string& status() const { return status_; }

  // Registration re-run in the background (rigid MI, as `mvw register`).
  void startRegistration();
  bool registering() const { return worker_.running(); }
  double registrationSeconds() const { return worker_.seconds(); }
  // Once a re-run has ended: the new anatomicalFromFunctional for the renderer (nothing if
  // it failed: the status says why).
  std::optional<glm::dmat4> finishRegistration();
  const std::string& registration() const { return registration_; }
  // For tests: the job startRegistration runs instead of registerRigid.
  void setRegistrationJob(RegistrationWorker::Job job) { job_ = std::move(job); }

  // What the panel shows and edits.
  const config::StudyConfig& study() const { return study_; }
  const Volume& anatomical() const { return anatomical_; }
  const Volume* functional() const { return functional_; }
  const ViewerScene& scene() const { return scene_; }
  render::RenderSettings& view3d() { return view3d_; }  // edits: markDirty the panes
  const render::RenderSettings& view3d() const { return view3d_; }
  const std::string& presetName() const { return presetName_; }
  double mprWindow() const { return mprWindow_; }
  double mprLevel() const { return mprLevel_; }
  const glm::dvec3& crosshair() const { return crosshair_; }
  int maximised() const { return maximised_; }  // -1: all four panes
  const render::Camera& paneCamera(int pane) const { return pane_(pane).camera; }
  bool paneRendered(int pane) const { return pane_(pane).rendered; }
  // The world point under (x, y) of an MPR pane, on its plane through the crosshair.
  glm::dvec3 onPlane(int pane, double x, double y) const;
  ViewerProbe probe(const glm::dvec3& world) const;

 private:
  struct PaneState {
    bool dirty = true;
    bool rendered = false;
    glm::ivec2 size{0};
    glm::ivec2 origin{0};
    render::Camera camera;  // of the last frame: clicks and the wheel move along its axes
    Image raw;  // as rendered: what `mvw render --no-annotate` gives for the saved state
  };
  PaneState& pane_(int pane) { return panes_[static_cast<std::size_t>(pane)]; }
  const PaneState& pane_(int pane) const { return panes_[static_cast<std::size_t>(pane)]; }
  void markMprDirty();
  config::ViewConfig viewConfigOf(int pane) const;

  const config::StudyConfig& study_;
  const Volume& anatomical_;
  const Volume* functional_;
  ViewerScene scene_;
  std::array<PaneState, kPaneCount> panes_;
  render::RenderSettings view3d_;
  std::string presetName_;
  double mprWindow_ = 0, mprLevel_ = 0;
  std::optional<ColorTable> mprColors_;  // the MPR panes' anatomy; none: grey
  Orbit orbit_ = Orbit::Off;
  std::vector<double> orbitAzimuths_;
  std::size_t orbitStep_ = 0;
  glm::dvec3 crosshair_{0.0};
  int maximised_ = -1;
  bool quit_ = false;
  std::string status_;
  std::optional<std::filesystem::path> screenshot_;
  std::optional<std::pair<int, std::filesystem::path>> paneScreenshot_;
  std::string registration_;
  RegistrationWorker::Job job_;
  RegistrationWorker worker_;  // last: joined before anything its job reads goes away
};

}  // namespace mvw::app
