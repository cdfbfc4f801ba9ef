#pragma once
// The viewer's --script (tests under Xvfb drive the window with it). One command per line:
//   key K [ctrl]                        a key, as typed (1-5, d, g, f, p, r, s, o, k, z, x, c, j,
//                                       l)
//   drag PANE dx dy [left|right|middle] a drag by fractions of the pane (default left)
//   drag-frames PANE dx dy N [BUTTON]   the same drag spread over N frames, each one a frame of
//                                       an interactive drag (the 3D pane renders coarse, as
//                                       under the mouse), then the frame that refines
//   click PANE x y                      a click at fractions of the pane (y down)
//   wheel PANE n [ctrl]                 n wheel notches (with Ctrl: an MPR pane zooms)
//   jump                                the next place to read (key J): hottest voxel, segments,
//                                       ROIs
//   iso VALUE                           the 3D pane's isovalue (the panel's slider)
//   zoom PANE FACTOR                    the pane's zoom times FACTOR (the MPR panes together)
//   pan PANE dx dy                      the pane's picture moved dx mm right, dy mm up (the MPR
//                                       panes together, by the same world displacement)
//   wait FRAMES                         let FRAMES frames pass
//   screenshot FILE                     the whole window as drawn, PNG
//   screenshot-pane PANE FILE           the pane's rectangle of the window as drawn, PNG
//   save-config FILE                    the state as a study config (Ctrl+S)
//   dump PANE FILE                      the pane's full-resolution render, without annotations
//   colormap 3d|mpr|overlay NAME        a colour map chooser (grey, grey-inverted, hot-iron, pet,
//                                       hot-metal-blue, pet-20-step, hot-metal)
//   colormap functional NAME            the PET/CT layout's functional pane and MIP
//   orbit spin|rock|off                 the rotating 3D view (keys O and K toggle it)
//   glyph-label N KIND|none             what label N of a label map gets (the panel's picker;
//                                       KIND: bumps, dimples, rings, ridges, cones, crosses)
//   layout NAME                         standard, pet-ct (axial), pet-ct-coronal, pet-ct-sagittal
//                                       (key L cycles them; ViewerState::setLayout)
//   register | wait-registration        re-run the registration in the background | wait for it
//   roi PANE x0 y0 x1 y1                a sphere ROI drawn by a drag: centre at (x0, y0) on the
//                                       pane's plane, radius the distance to (x1, y1), in mm
//   ruler PANE x0 y0 x1 y1              a distance ruler from (x0, y0) to (x1, y1)
//   hover PANE x y                      the cursor over a pane (the value readout)
//   sphere L P S R                      a sphere ROI by its centre (LPS mm) and radius (mm); the
//                                       crosshair goes to its centre
//   roi-stats FILE                      every sphere's statistics, JSON (mvw stats's fields)
//   clear-measurements                  no sphere, no ruler
//   pacs-server NAME                    the PACS panel opens on the server of servers.json so
//                                       named (PacsBrowser)
//   pacs-search [KEY=VALUE ...]         a study search, waited for; KEY: patient-id,
//                                       patient-name, study-date, modality, accession
//   pacs-study N|UID                    the N-th study found (1: the first) or the one of that
//                                       Study Instance UID; its series asked for, waited for
//   pacs-series ROLE SERIES|none        the series ROLE (anatomical, functional, segmentation)
//                                       takes: its UID, number, modality or description
//   pacs-registration METHOD            none, rigid, affine (the study's registration rule)
//   pacs-open [nowait]                  retrieve and open the chosen series as the study shown;
//                                       waits until it is open or has failed (the panel says
//                                       why, and the current study stays); nowait: goes on
//                                       while it runs (the window keeps drawing)
//   pacs-wait [progress]                wait for the PACS window's running step to end; progress:
//                                       only until its retrieve has received an instance
//   pacs-report FILE                    the PACS panel's state, JSON: server, studies, series,
//                                       chosen series, status, error
//   quit
// PANE: 3d, axial, coronal, sagittal; or mip, anatomical, functional, fused (the same slots,
// as the PET/CT layout shows them). Blank lines and lines starting with # are skipped (each
// still takes a frame, as every line does). The whole script is checked when it is read, so a
// typo is reported before the window opens, naming the file and the line; what only the run
// can tell (a server not in the list, a series that matches none) names them too.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mvw/viewer/PacsBrowser.h"
#include "mvw/viewer/ViewerState.h"

namespace mvw::viewer {

class ViewerScript {
 public:
  struct Command {
    enum class Kind {
      Nothing,  // blank line or comment
      Key,
      Drag,
      DragFrames,
      Click,
      Wheel,
      Zoom,
      Pan,
      Iso,
      Jump,
      Wait,
      Screenshot,
      PaneScreenshot,
      SaveConfig,
      Dump,
      Colormap,
      Orbit,
      Layout,
      GlyphLabel,
      Register,
      WaitRegistration,
      Hover,
      Roi,
      Ruler,
      Sphere,
      RoiStats,
      ClearMeasurements,
      PacsServer,
      PacsSearch,
      PacsStudy,
      PacsSeries,
      PacsRegistration,
      PacsOpen,
      PacsWait,
      PacsReport,
      Quit
    };
    Kind kind = Kind::Nothing;
    int line = 0;  // 1-based
    char key = 0;  // upper case
    bool ctrl = false;
    int pane = k3d;
    double x = 0.0, y = 0.0;    // drag, pan: dx, dy; click: x, y; wheel: x = notches; zoom: x
    double x1 = 0.0, y1 = 0.0;  // roi, ruler: where the drag ends
    config::SphereMeasurement sphere;
    MouseButton button = MouseButton::Left;
    int frames = 0;
    std::filesystem::path file;
    ColorTarget target = ColorTarget::View3d;
    ColorMap colormap = ColorMap::Grey;
    viewer::Orbit orbit = viewer::Orbit::Off;
    config::ViewerLayout layout = config::ViewerLayout::Standard;
    int label = 0;  // glyph-label
    config::LabelGlyphKind labelKind = config::LabelGlyphKind::Bumps;
    std::string text;  // pacs-server: the name; pacs-study: N or UID; pacs-series: SERIES
    pacs::StudyQuery query;
    PacsBrowser::Role role = PacsBrowser::Role::Anatomical;
    config::RegistrationMethod registration = config::RegistrationMethod::None;
  };

  ViewerScript() = default;
  // Throws InputError naming `source` and the line for anything that is not a command above.
  static ViewerScript parse(const std::string& text, const std::filesystem::path& source);
  static ViewerScript load(const std::filesystem::path& file);  // parse() of the file's text

  bool empty() const { return commands_.empty(); }
  const std::vector<Command>& commands() const { return commands_; }
  // Called once per fully drawn frame: runs the next line on the state (or waits); returns
  // false once every line has run. Errors the state throws (a file that cannot be written)
  // propagate. state: null while no study is open (a line that needs one is an InputError);
  // pacs: the PACS browser the pacs-* lines drive (null: they are an InputError).
  bool step(ViewerState* state, PacsBrowser* pacs);
  bool step(ViewerState& state) { return step(&state, nullptr); }
  // While no study is open, a screenshot line asks here (the window loop takes it).
  ViewerRequests& idleRequests() { return idleRequests_; }

 private:
  std::vector<Command> commands_;
  std::filesystem::path source_;
  std::size_t next_ = 0;
  bool waitingPacs_ = false;      // a pacs-* line's step runs: the next line waits for it
  bool waitingProgress_ = false;  // ... only until its retrieve has received an instance
  ViewerRequests idleRequests_;
  void runPacs(const Command& c, PacsBrowser* pacs);
  int wait_ = 0;
  // The next 1/N of the drag-frames command in progress, as an interactive frame.
  void dragIncrement(ViewerState& state);
  // A drag-frames command in progress (its index in commands_) and the frames it has left.
  std::optional<std::size_t> dragging_;
  int dragFramesLeft_ = 0;
};

}  // namespace mvw::viewer
