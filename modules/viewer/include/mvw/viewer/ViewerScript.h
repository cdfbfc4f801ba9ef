#pragma once
// The viewer's --script (tests under Xvfb drive the window with it). One command per line, each
// one an entry of the command table in ViewerScript.cpp (name, arguments, what it does, an
// example, its parser); reference() prints that table as docs/user-guide/view.md's script
// reference has it.
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
      Maximise,
      Zoom,
      Pan,
      Iso,
      Jump,
      Wait,
      Screenshot,
      PaneScreenshot,
      SaveConfig,
      Dump,
      PaneReport,
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

  // One command of the language, as the reference describes it.
  struct CommandInfo {
    const char* name;       // "drag"
    const char* arguments;  // "PANE dx dy [left|right|middle]" ("" for none)
    const char* help;       // what it does
    const char* example;    // a whole line that parses ("drag 3d 0.15 0.05")
  };
  // Every command, in the reference's order.
  static std::vector<CommandInfo> commandInfo();
  // The script reference as Markdown: a table of every command between two comment lines, the
  // section of docs/user-guide/view.md that `mvw view --script-reference` prints.
  static std::string reference();

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
