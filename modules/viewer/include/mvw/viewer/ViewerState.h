#pragma once
// What `mvw view` shows and how input changes it, without a window or GL: the four panes
// (3D and the axial, coronal and sagittal MPR) and their frames, the 3D settings, mode and
// preset, the linked crosshair, the MPR window/level and colour maps, the camera maths of
// dragging, clicking and the wheel, the values under the cursor, and the saved state. The
// mouse, the keyboard, the panel and the --script interpreter all act through this class; the
// window loop renders what it asks for. It owns the parts with jobs of their own, each reached
// by its accessor: requests() (what the window loop acts on), measurements() (ROIs and rulers,
// which see the panes through PaneGeometry), registration() (the re-run) and orbit().
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Image.h"
#include "mvw/core/Volume.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Camera.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/viewer/PaneGeometry.h"
#include "mvw/viewer/ViewerMeasurements.h"
#include "mvw/viewer/ViewerOrbit.h"
#include "mvw/viewer/ViewerRegistration.h"
#include "mvw/viewer/ViewerRequests.h"

namespace mvw::viewer {

enum class MouseButton { Left = 0, Right = 1, Middle = 2 };
// Which image a colour map chooser sets: the 3D pane's projection, the MPR panes' anatomy, or
// the functional overlay (MPR) and fusion (3D).
// Functional: the PET/CT layout's functional pane and its MIP (grey-inverted by default).
enum class ColorTarget { View3d, Mpr, Overlay, Functional };

// What the renderer knows about the volumes that the state's maths need (the renderer holds
// them in GL; a test gives them by hand).
struct ViewerScene {
  glm::dvec3 centre{0.0};  // the sphere the cameras frame
  double radius = 1.0;
  std::pair<double, double> valueRange{0.0, 1.0};
  std::pair<double, double> functionalRange{0.0, 1.0};
  std::string registration = "none";  // how the functional volume was placed, for the panel
  // The placement the renderer draws the functional volume with (world LPS mm to world).
  glm::dmat4 anatomicalFromFunctional{1.0};
  // Places the reader jumps to besides the hottest voxel and the ROIs: each segment of the
  // study's segmentation by its name, at its centre (world LPS mm, where the outlines are).
  std::vector<std::pair<std::string, glm::dvec3>> segmentCentres;
};

// The volumes' values under a world point (the panel's cursor readout): the anatomical voxel
// nearest the point, and the functional volume at that voxel's centre as the renderer samples
// it (through the placement, trilinear between the functional voxels' centres, clamped at the
// edge, inside its voxel box).
struct ViewerProbe {
  bool anatomicalInside = false, functionalInside = false;
  double anatomical = 0.0, functional = 0.0;
  glm::dvec3 at{0.0};  // the anatomical voxel's centre, LPS mm
};

class ViewerState : public PaneGeometry {
 public:
  // The 3D pane opens on the study's first 3D view as `mvw render` would render it; the MPR
  // panes take the first MPR view's window. The study and the volumes must outlive the state
  // (a running registration reads them).
  ViewerState(const config::StudyConfig& study, const Volume& anatomical, const Volume* functional,
              ViewerScene scene);
  ~ViewerState() override = default;  // a running registration is waited for, never abandoned
  ViewerState(const ViewerState&) = delete;
  ViewerState& operator=(const ViewerState&) = delete;

  static const char* paneName(int pane);  // 3d, axial, coronal, sagittal
  // The inverse; the PET/CT layout's names are accepted too: mip (the 3D pane's slot),
  // anatomical (axial's), functional (coronal's), fused (sagittal's).
  static std::optional<int> paneNamed(const std::string& name);
  // The layout (issue 36 item 2; config::ViewerLayout): standard, the 3D pane and the axial,
  // coronal and sagittal MPR; PET/CT, the four panes' slots show the functional volume's
  // rotating MIP (the 3D slot), the anatomical MPR (axial's slot: no overlay), the functional
  // MPR (coronal's: the functional volume alone, in the functional colour map; without a
  // functional volume the anatomical one in that map) and the fused MPR (sagittal's), the
  // three MPRs of one plane in step (one zoom, pan and crosshair). Setting a PET/CT layout
  // starts the MIP spinning; key L cycles standard, pet-ct (axial), coronal, sagittal.
  void setLayout(config::ViewerLayout layout);
  config::ViewerLayout layout() const { return layout_; }
  bool petCtLayout() const { return layout_ != config::ViewerLayout::Standard; }
  // The plane an MPR pane shows (its slot's in the standard layout, the layout's in PET/CT).
  render::StandardView mprView(int pane) const;
  // Whether the pane renders the functional volume as its image (the PET/CT layout's MIP of a
  // study with a functional volume): the window renders it with a renderer of that volume.
  bool paneShowsFunctional(int pane) const;
  // What the pane shows, for its title on screen: "3D", "axial", ...; in PET/CT "MIP PET WB",
  // "CT Chest", "PET WB", "fused".
  std::string paneTitle(int pane) const;
  // Where the panel draws each slot in the 2 x 2 grid (0 top left, 1 top right, 2 bottom left,
  // 3 bottom right): the slot order in the standard layout; in PET/CT anatomical, functional,
  // fused, MIP.
  int paneCell(int pane) const;
  // The volume's name in readouts, statistics and colour bars (study::volumeName): "MR relCBF",
  // "CT Cranium"; `role` ("anatomical", "functional") where it names neither.
  static std::string volumeName(const Volume& volume, const char* role);
  // The 3D pane's modes, in the order of the keys 1-5.
  static std::span<const render::RenderMode> modes3d();

  // Input. Drags and clicks are in fractions of the pane (y down); steps are wheel notches.
  void drag(int pane, double dx, double dy, MouseButton button, bool ctrl);
  void click(int pane, double x, double y);
  // The wheel: the 3D pane zooms; an MPR pane scrolls slices, or zooms with Ctrl.
  void wheel(int pane, double steps, bool ctrl = false);
  // key: an upper-case letter or digit ('1'..'5' modes, 'D', 'G', 'F', 'P', 'R', 'S', 'O' spin,
  // 'K' rock, 'Z' MPR fit, 'X' MPR one screen pixel per voxel, 'C' MPR panes centred on the
  // crosshair, 'J' jump, 'L' next layout); other keys do nothing.
  void key(char key, bool ctrl);
  void toggleMaximised(int pane);
  // Zoom and pan (issue 36 item 1). The MPR panes are linked: one zoom, and one pan in world
  // terms (a point moved into view on one pane is in view on the others); the 3D pane has its
  // own camera. zoomPane multiplies the zoom (0.1 .. 50 for MPR, 0.1 .. 20 in 3D); panPane
  // moves the picture right and up by millimetres on the pane. mprFit: the whole volume (zoom
  // 1, no pan); mprOneToOne: one screen pixel per voxel of the anatomical volume's finest
  // spacing on the axial pane, the pan kept.
  void zoomPane(int pane, double factor);
  void panPane(int pane, double rightMm, double upMm);
  void mprFit();
  void mprOneToOne();
  void mprCentreOnCrosshair();  // the pan that puts the crosshair in every MPR pane's middle
  // Reading a PET (issue 36 item 4): the crosshair to the next of the hottest voxel (of the
  // functional volume where there is one, else of the anatomical), each segment's centre and
  // each sphere ROI's centre, in that order and round again; the MPR panes centre on it and the
  // status line names it. Returns what it jumped to ("" when there is nothing).
  std::string jumpNext();
  double mprZoom() const { return mprZoom_; }
  const glm::dvec3& mprPan() const { return mprPan_; }  // world mm the MPR pictures are moved
  void setMode(render::RenderMode mode);                // one of modes3d()
  void setPreset(const std::string& name);
  void setMprWindow(const WindowLevel& window);
  // Colour maps (grey for the images and hot metal for the overlay are the defaults); the 3D
  // pane's shows in MIP, MinIP and average.
  void setColormap(ColorTarget target, ColorMap map);
  ColorMap colormap(ColorTarget target) const;
  // Glyphs on chosen labels of a label map (issue 15 item 4), as the config's glyphs.labels:
  // a label gets bumps, dimples or none. While no label is chosen every label above the
  // attribute window carries glyphs. The names come from the atlas's label table beside the
  // functional volume (empty without one).
  void setGlyphLabel(int label, config::LabelGlyphKind kind);
  const std::map<int, std::string>& labelNames() const { return labelNames_; }

  // The rotating 3D view (ViewerOrbit), from the azimuth shown now; the same toggle again
  // switches it off.
  void setOrbit(Orbit orbit) { orbit_.start(orbit, view3d_.camera.azimuthDeg); }
  void toggleOrbit(Orbit orbit) { setOrbit(orbit_.mode() == orbit ? Orbit::Off : orbit); }
  const ViewerOrbit& orbit() const { return orbit_; }
  // The window calls this once per drawn frame: the 3D camera to the orbit's next azimuth
  // (the 3D pane dirty).
  void advanceOrbit();

  // Rendering: the window loop sets each pane's size, renders the panes that need it with
  // renderSettings(), and reports each frame back.
  // Marks the pane dirty when it changes. The 3D pane's glyphs, where the study's view leaves
  // their spacing open and the panel has not set one, take the spacing `mvw render` derives
  // for that view at the pane's size (study::applyGlyphScale): a maximised pane reads as a
  // render at its size does.
  void setPaneSize(int pane, glm::ivec2 size);
  // Where the panel drew the pane this frame (window pixels, top left; size: setPaneSize).
  void setPaneOrigin(int pane, glm::ivec2 topLeft) { pane_(pane).origin = topLeft; }
  glm::ivec2 paneOrigin(int pane) const { return pane_(pane).origin; }
  glm::ivec2 paneSize(int pane) const { return pane_(pane).size; }
  bool needsRender(int pane) const;
  // As rendered at the pane's size; while interacting the 3D pane renders coarse: a
  // dragDivisor()-th of its size a side, at that many times the smallest spacing per step.
  render::RenderSettings renderSettings(int pane, bool interacting = false) const;
  // Adapted to the drag frames' time (rendered's milliseconds): from 2, one up while a frame
  // takes longer than kDragFrameBudgetMs (at most kMaxDragDivisor), one down while it takes
  // under a third of that, so a large volume stays above 10 frames/s while dragged.
  int dragDivisor() const { return dragDivisor_; }
  static constexpr double kDragFrameBudgetMs = 70.0;
  static constexpr int kMaxDragDivisor = 6;
  std::string caption(int pane, const render::RenderSettings& settings) const;
  // What the pane's glyphs mean (empty without glyphs), as `mvw render` burns it in.
  render::GlyphLegend glyphLegend(int pane, const render::RenderSettings& settings) const;
  // `milliseconds`: what the render took (adapts dragDivisor on interactive 3D frames).
  void rendered(int pane, const render::Camera& camera, Image raw, bool interacting,
                double milliseconds = 0.0);
  bool anyDirty() const;
  // Why the pane's last frame shows nothing (empty where it shows something): an isovalue
  // outside the volume's values, a preset that makes them all transparent, a plane or window
  // that leaves nothing; the panel writes it on the pane (issue 36 item 5).
  std::string emptyPaneMessage(int pane) const;
  void markDirty(int pane) { panes_[static_cast<std::size_t>(pane)].dirty = true; }
  void markAllDirty();

  // Files.
  void saveConfig(const std::filesystem::path& file) const;      // every pane as a study view
  void dump(int pane, const std::filesystem::path& file) const;  // the pane as rendered, raw

  // What the panel shows and edits.
  const config::StudyConfig& study() const { return study_; }
  const Volume& anatomical() const { return anatomical_; }
  const Volume* functional() const { return functional_; }
  const ViewerScene& scene() const { return scene_; }
  render::RenderSettings& view3d() { return view3d_; }  // edits: markDirty the panes
  const render::RenderSettings& view3d() const { return view3d_; }
  const std::string& presetName() const { return presetName_; }
  const WindowLevel& mprWindow() const { return mprWindow_; }
  // The PET/CT layout's functional pane and rotating MIP: the functional volume alone, in its
  // own window (not the glyphs' or the overlay's): the study's first MPR view's
  // functional_window, else study::defaultFunctionalDisplayWindow from the data.
  const ValueWindow& functionalDisplayWindow() const { return functionalDisplay_; }
  void setFunctionalDisplayWindow(double low, double high);
  int maximised() const { return maximised_; }  // -1: all four panes
  // The panes' geometry (PaneGeometry): the last frames' cameras, the crosshair, and the world
  // point under (x, y) of an MPR pane, on its plane through the crosshair.
  const glm::dvec3& crosshair() const override { return crosshair_; }
  const render::Camera& paneCamera(int pane) const override { return pane_(pane).camera; }
  bool paneRendered(int pane) const override { return pane_(pane).rendered; }
  glm::dvec3 onPlane(int pane, double x, double y) const override;
  ViewerProbe probe(const glm::dvec3& world) const;
  // The cursor over an MPR pane (the readout's point, on the pane's plane); the mouse moves it,
  // and so does the script's hover.
  void setCursor(int pane, double x, double y) { cursor_ = {pane, onPlane(pane, x, y)}; }
  std::optional<std::pair<int, glm::dvec3>> cursor() const { return cursor_; }
  // The readout at a point: "CT Cranium 45 HU | PET WB 3.21 SUVbw" (each volume by
  // volumeName, each value with its unit or "(no unit)"; "outside" where the point is outside
  // a volume).
  std::string readout(const glm::dvec3& world) const;

  // The crosshair to a point (the MPR panes then cut it), e.g. to an ROI's centre.
  void setCrosshair(const glm::dvec3& world) { crosshair_ = world, markMprDirty(); }
  void setSegmentOutlines(bool on) { segmentOutlines_ = on, markMprDirty(); }
  bool segmentOutlines() const { return segmentOutlines_; }

  // The parts with jobs of their own.
  // What the window loop acts on once a frame is drawn (screenshots, quit), the status line.
  ViewerRequests& requests() { return requests_; }
  const ViewerRequests& requests() const { return requests_; }
  // The sphere ROIs and rulers on the MPR panes, and the mouse tool that draws them (saved
  // with the state as the study's "measurements", restored on opening).
  ViewerMeasurements& measurements() { return measurements_; }
  const ViewerMeasurements& measurements() const { return measurements_; }
  // The registration re-run in the background (MI with the study's registration options, as
  // placing the study and `mvw register STUDY.json` run it).
  ViewerRegistration& registration() { return registration_; }
  const ViewerRegistration& registration() const { return registration_; }
  // The window calls this once per frame: once a re-run has ended, the new
  // anatomicalFromFunctional for the renderer (the panes redraw, the functional ROI statistics
  // follow it); nothing while it runs or if it failed (the status line says why).
  std::optional<glm::dmat4> finishRegistration();

 private:
  int dragDivisor_ = 2;
  struct PaneState {
    bool dirty = true;
    bool rendered = false;
    bool empty = false;  // the last frame is one colour: nothing of the volume shows
    glm::ivec2 size{0};
    glm::ivec2 origin{0};
    render::Camera camera;  // of the last frame: clicks and the wheel move along its axes
    Image raw;  // as rendered: what `mvw render --no-annotate` gives for the saved state
  };
  PaneState& pane_(int pane) { return panes_[static_cast<std::size_t>(pane)]; }
  const PaneState& pane_(int pane) const { return panes_[static_cast<std::size_t>(pane)]; }
  void markMprDirty();
  // The pane's settings and view as `layout` would show it (saved states are the standard
  // layout's views and the layout's name).
  render::RenderSettings settingsIn(config::ViewerLayout layout, int pane, bool interacting) const;
  config::ViewConfig viewConfigOf(int pane, config::ViewerLayout layout) const;
  void fitGlyphSpacing();  // setPaneSize's glyph spacing for the 3D pane's size

  const config::StudyConfig& study_;
  const Volume& anatomical_;
  const Volume* functional_;
  ViewerScene scene_;
  std::array<PaneState, kPaneCount> panes_;
  render::RenderSettings view3d_;
  // The study's view that set view3d_ up, while its glyph spacing follows the 3D pane's size
  // (fitGlyphSpacing), and the spacing it last gave: another one was set by the panel.
  std::optional<config::ViewConfig> glyphScaleView_;
  double glyphScaleSpacingMm_ = 0.0;
  std::string presetName_;
  WindowLevel mprWindow_;
  ValueWindow functionalDisplay_{0.0, 1.0};
  double mprZoom_ = 1.0;
  glm::dvec3 mprPan_{0.0};
  std::map<int, std::string> labelNames_;
  std::optional<ColorTable> mprColors_;  // the MPR panes' anatomy; none: grey
  ColorTable functionalColors_;          // the PET/CT layout's functional pane and MIP
  config::ViewerLayout layout_ = config::ViewerLayout::Standard;
  bool segmentOutlines_ = true;  // the MPR panes outline the study's segmentation
  std::optional<std::pair<int, glm::dvec3>> cursor_;
  ViewerMeasurements measurements_;  // after scene_: it starts from scene_'s placement
  ViewerOrbit orbit_;
  glm::dvec3 crosshair_{0.0};
  int maximised_ = -1;
  std::size_t nextJump_ = 0;
  std::optional<glm::dvec3> hottest_;  // found on the first jump
  ViewerRequests requests_;
  // Last: destroyed first, so a running re-run is waited for while everything else is there.
  ViewerRegistration registration_;
};

}  // namespace mvw::viewer
