#include "mvw/viewer/ViewerScript.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/viewer/OpenedStudy.h"

namespace mvw::viewer {

namespace {

using Command = ViewerScript::Command;
using Kind = Command::Kind;

// Every message about a script line is formed here: "line N: problem", with the script's own
// bytes the problem quotes (a word, a server's name) made printable, so a stray control byte in
// the file cannot garble the terminal or the log that shows the message.
[[noreturn]] void scriptError(const std::filesystem::path& source, int line,
                              const std::string& problem) {
  throw InputError(source, "line " + std::to_string(line) + ": " + printable(problem));
}

// The tokens of one line, consumed in order; every complaint names the file and the line.
class LineReader {
 public:
  LineReader(const std::string& line, const std::filesystem::path& source, int number)
      : source_(source), number_(number) {
    std::istringstream in(line);
    for (std::string t; in >> t;) tokens_.push_back(t);
  }
  bool empty() const { return tokens_.empty(); }
  bool more() const { return next_ < tokens_.size(); }
  [[noreturn]] void fail(const std::string& problem) const {
    scriptError(source_, number_, problem);
  }
  std::string word(const char* what) {
    if (!more()) fail(command() + ": missing " + what);
    return tokens_[next_++];
  }
  double number(const char* what) {
    const std::string t = word(what);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
      fail(command() + ": " + what + " '" + t + "' is not a number");
    return v;
  }
  int pane() {
    const std::string t = word("pane");
    if (auto p = ViewerState::paneNamed(t)) return *p;
    fail("unknown pane '" + t +
         "' (3d, axial, coronal, sagittal; in the PET/CT layout also mip, anatomical, "
         "functional, fused)");
  }
  // The rest of the line, its words joined by one space (a server's name, a description).
  std::string rest(const char* what) {
    if (!more()) fail(command() + ": missing " + what);
    std::string text;
    while (more()) text += (text.empty() ? "" : " ") + tokens_[next_++];
    return text;
  }
  void end() const {
    if (more()) fail(command() + ": unexpected '" + tokens_[next_] + "'");
  }
  std::string command() const { return tokens_.front(); }

 private:
  const std::filesystem::path& source_;
  int number_;
  std::vector<std::string> tokens_;
  std::size_t next_ = 0;
};

// The parsers of the commands' arguments, one per command (or per family of commands that share
// their arguments): each reads what follows the command's name into `c`, whose kind is set.

// An optional trailing "ctrl" (key, wheel).
void parseCtrl(LineReader& in, Command& c) {
  if (!in.more()) return;
  const std::string mod = in.word("modifier");
  if (mod != "ctrl") in.fail(in.command() + ": unknown modifier '" + mod + "' (ctrl)");
  c.ctrl = true;
}

// A whole number within [lo, hi]; `problem` says the range when it is not.
int wholeNumber(LineReader& in, const char* what, double lo, double hi,
                const std::string& problem) {
  const double v = in.number(what);
  if (v < lo || v != std::floor(v) || v > hi) in.fail(problem);
  return static_cast<int>(v);
}

// An MPR pane (axial, coronal, sagittal or their PET/CT names); `problem` completes
// "COMMAND: " when the line names the 3D pane.
void mprPane(LineReader& in, Command& c, const char* problem) {
  c.pane = in.pane();
  if (c.pane == k3d) in.fail(in.command() + ": " + problem);
}

void parseKey(LineReader& in, Command& c) {
  const std::string k = in.word("key");
  if (k.size() != 1)
    in.fail("key: '" + k + "' is not one key (1-5, d, g, f, p, r, s, o, k, z, x, c, j, l)");
  c.key = static_cast<char>(std::toupper(static_cast<unsigned char>(k[0])));
  parseCtrl(in, c);
}

void parseDrag(LineReader& in, Command& c) {
  c.pane = in.pane();
  c.x = in.number("dx");
  c.y = in.number("dy");
  if (c.kind == Kind::DragFrames)
    c.frames = wholeNumber(in, "frame count", 1, 1e5,
                           "drag-frames: the frame count must be a whole number from 1 to 100000");
  if (!in.more()) return;
  const std::string b = in.word("button");
  if (b == "left")
    c.button = MouseButton::Left;
  else if (b == "right")
    c.button = MouseButton::Right;
  else if (b == "middle")
    c.button = MouseButton::Middle;
  else
    in.fail(in.command() + ": unknown button '" + b + "' (left, right, middle)");
}

void parsePanePoint(LineReader& in, Command& c) {  // click
  c.pane = in.pane();
  c.x = in.number("x");
  c.y = in.number("y");
}

void parseWheel(LineReader& in, Command& c) {
  c.pane = in.pane();
  c.x = in.number("notches");
  parseCtrl(in, c);
}

void parseIso(LineReader& in, Command& c) { c.x = in.number("value"); }

void parsePane(LineReader& in, Command& c) { c.pane = in.pane(); }

void parseZoom(LineReader& in, Command& c) {
  c.pane = in.pane();
  c.x = in.number("factor");
  if (!(c.x >= 0.01 && c.x <= 100)) in.fail("zoom: the factor must lie in 0.01 .. 100");
}

void parsePan(LineReader& in, Command& c) {
  c.pane = in.pane();
  c.x = in.number("dx");
  c.y = in.number("dy");
  if (!(std::abs(c.x) <= 1e5 && std::abs(c.y) <= 1e5)) in.fail("pan: dx and dy within +-1e5 mm");
}

void parseHover(LineReader& in, Command& c) {
  mprPane(in, c, "reads values on an MPR pane (axial, coronal, sagittal)");
  c.x = in.number("x");
  c.y = in.number("y");
}

void parseWait(LineReader& in, Command& c) {
  c.frames = wholeNumber(in, "frame count", 0, 1e6,
                         "wait: the frame count must be a whole number from 0 to 1000000");
}

void parseFile(LineReader& in, Command& c) { c.file = in.word("file"); }

void parsePaneFile(LineReader& in, Command& c) {  // screenshot-pane, dump
  c.pane = in.pane();
  c.file = in.word("file");
}

void parseColormap(LineReader& in, Command& c) {
  const std::string target = in.word("target");
  if (target == "3d")
    c.target = ColorTarget::View3d;
  else if (target == "mpr")
    c.target = ColorTarget::Mpr;
  else if (target == "overlay")
    c.target = ColorTarget::Overlay;
  else if (target == "functional")
    c.target = ColorTarget::Functional;
  else
    in.fail("colormap: unknown target '" + target + "' (3d, mpr, overlay, functional)");
  const std::string name = in.word("colour map");
  const std::optional<ColorMap> map = parseColorMap(name);
  if (!map) {
    std::string names;
    for (const auto& n : colorMapNames()) names += (names.empty() ? "" : ", ") + n;
    in.fail("colormap: unknown colour map '" + name + "' (" + names + ")");
  }
  c.colormap = *map;
}

void parseLayout(LineReader& in, Command& c) {
  const std::string name = in.word("layout");
  const std::optional<config::ViewerLayout> layout = config::parseViewerLayout(name);
  if (!layout)
    in.fail("layout: unknown layout '" + name + "' (" + config::viewerLayoutList() + ")");
  c.layout = *layout;
}

void parseOrbit(LineReader& in, Command& c) {
  const std::string mode = in.word("mode");
  if (mode == "spin")
    c.orbit = Orbit::Spin;
  else if (mode == "rock")
    c.orbit = Orbit::Rock;
  else if (mode == "off")
    c.orbit = Orbit::Off;
  else
    in.fail("orbit: unknown mode '" + mode + "' (spin, rock, off)");
}

void parseGlyphLabel(LineReader& in, Command& c) {
  c.label = wholeNumber(
      in, "label", 1, kMaxGlyphLabel,
      "glyph-label: the label must be a whole number from 1 to " + std::to_string(kMaxGlyphLabel));
  const std::string kind = in.word("kind");
  const std::optional<config::LabelGlyphKind> k = config::parseLabelGlyphKind(kind);
  if (!k)
    in.fail("glyph-label: unknown kind '" + kind +
            "' (bumps, dimples, rings, ridges, cones, crosses, none)");
  c.labelKind = *k;
}

void parseDragOnMpr(LineReader& in, Command& c) {  // roi, ruler
  mprPane(in, c, "draws on an MPR pane (axial, coronal, sagittal)");
  c.x = in.number("x0");
  c.y = in.number("y0");
  c.x1 = in.number("x1");
  c.y1 = in.number("y1");
}

void parseSphere(LineReader& in, Command& c) {
  for (double& v : c.sphere.centre) v = in.number("centre (L P S mm)");
  c.sphere.radiusMm = in.number("radius");
  if (!(c.sphere.radiusMm > 0)) in.fail("sphere: the radius must be above 0 mm");
}

void parsePacsServer(LineReader& in, Command& c) { c.text = in.rest("server name"); }

void parsePacsSearch(LineReader& in, Command& c) {
  while (in.more()) {
    const std::string kv = in.word("KEY=VALUE");
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) in.fail("pacs-search: '" + kv + "' is not KEY=VALUE");
    const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
    if (key == "patient-id")
      c.query.patientId = value;
    else if (key == "patient-name")
      c.query.patientName = value;
    else if (key == "study-date")
      c.query.studyDate = value;
    else if (key == "modality")
      c.query.modality = value;
    else if (key == "accession")
      c.query.accession = value;
    else
      in.fail("pacs-search: unknown key '" + key +
              "' (patient-id, patient-name, study-date, modality, accession)");
  }
}

void parsePacsStudy(LineReader& in, Command& c) { c.text = in.word("study (N or UID)"); }

void parsePacsSeries(LineReader& in, Command& c) {
  const std::string role = in.word("role");
  if (role == "anatomical")
    c.role = PacsBrowser::Role::Anatomical;
  else if (role == "functional")
    c.role = PacsBrowser::Role::Functional;
  else if (role == "segmentation")
    c.role = PacsBrowser::Role::Segmentation;
  else
    in.fail("pacs-series: unknown role '" + role + "' (anatomical, functional, segmentation)");
  c.text = in.rest("series (UID, number, modality, description or none)");
}

void parsePacsRegistration(LineReader& in, Command& c) {
  const std::string method = in.word("method");
  if (method == "none")
    c.registration = config::RegistrationMethod::None;
  else if (method == "rigid")
    c.registration = config::RegistrationMethod::Rigid;
  else if (method == "affine")
    c.registration = config::RegistrationMethod::Affine;
  else
    in.fail("pacs-registration: unknown method '" + method + "' (none, rigid, affine)");
}

// An optional single option word (pacs-open nowait, pacs-wait progress): frames = -1 when given.
void parseOption(LineReader& in, Command& c, const char* option) {
  if (!in.more()) return;
  const std::string word = in.word(option);
  if (word != option) in.fail(in.command() + ": unknown option '" + word + "' (" + option + ")");
  c.frames = -1;
}

void parsePacsOpen(LineReader& in, Command& c) { parseOption(in, c, "nowait"); }
void parsePacsWait(LineReader& in, Command& c) { parseOption(in, c, "progress"); }

// One script command: how the reference names it and says what it does, a line that uses it,
// its kind and the parser of its arguments (none: the command takes none).
struct Entry {
  ViewerScript::CommandInfo info;
  Kind kind;
  void (*parse)(LineReader& in, Command& c);
};

// Every command, in the order of the reference (docs/user-guide/view.md's table is generated
// from it: ViewerScript::reference()).
const Entry kCommands[] = {
    {{"key", "K [ctrl]", "a key, as typed (1-5, d, g, f, p, r, s, o, k, z, x, c, j, l)",
      "key s ctrl"},
     Kind::Key,
     parseKey},
    {{"drag", "PANE dx dy [left|right|middle]", "a drag by fractions of the pane (default left)",
      "drag 3d 0.15 0.05"},
     Kind::Drag,
     parseDrag},
    {{"drag-frames", "PANE dx dy N [left|right|middle]",
      "the same drag spread over N frames (1 .. 100000), each one a frame of an interactive drag "
      "(the 3D pane renders coarse, as under the mouse), then the frame that refines",
      "drag-frames 3d 0.2 0 6"},
     Kind::DragFrames,
     parseDrag},
    {{"click", "PANE x y", "a click at fractions of the pane (y down)", "click axial 0.55 0.45"},
     Kind::Click,
     parsePanePoint},
    {{"wheel", "PANE n [ctrl]", "n wheel notches (with Ctrl an MPR pane zooms)", "wheel coronal 4"},
     Kind::Wheel,
     parseWheel},
    {{"maximise", "PANE",
      "the pane maximised, or all four panes back if it is (a double click on it); the 3D "
      "pane's automatic glyph spacing follows its new size",
      "maximise 3d"},
     Kind::Maximise,
     parsePane},
    {{"jump", "", "the next place to read (key J): hottest voxel, segments, ROIs", "jump"},
     Kind::Jump,
     nullptr},
    {{"iso", "VALUE", "the 3D pane's isovalue (the panel's slider)", "iso 300"},
     Kind::Iso,
     parseIso},
    {{"zoom", "PANE FACTOR", "the pane's zoom times FACTOR, 0.01 .. 100 (the MPR panes together)",
      "zoom axial 2.5"},
     Kind::Zoom,
     parseZoom},
    {{"pan", "PANE dx dy",
      "the pane's picture moved dx mm right, dy mm up, each within +-1e5 mm (the MPR panes "
      "together, by the same world displacement)",
      "pan sagittal 3 -4"},
     Kind::Pan,
     parsePan},
    {{"hover", "PANE x y", "the cursor over an MPR pane (the value readout)",
      "hover axial 0.5 0.5"},
     Kind::Hover,
     parseHover},
    {{"wait", "FRAMES", "let FRAMES frames pass (0 .. 1000000)", "wait 2"}, Kind::Wait, parseWait},
    {{"screenshot", "FILE", "the whole window as drawn, PNG", "screenshot out/window.png"},
     Kind::Screenshot,
     parseFile},
    {{"screenshot-pane", "PANE FILE", "the pane's rectangle of the window as drawn, PNG",
      "screenshot-pane sagittal out/sagittal.png"},
     Kind::PaneScreenshot,
     parsePaneFile},
    {{"dump", "PANE FILE", "the pane's render at full resolution, without annotations",
      "dump 3d out/3d.png"},
     Kind::Dump,
     parsePaneFile},
    {{"pane-report", "FILE",
      "every pane as the window draws it, JSON: name, title, mode, window (low, high), colour "
      "bar (low, high, unit, title, colour map; null: none), caption; and the readout at the "
      "cursor (hover), else at the crosshair",
      "pane-report out/panes.json"},
     Kind::PaneReport,
     parseFile},
    {{"save-config", "FILE", "the state as a study config (Ctrl+S)", "save-config out/saved.json"},
     Kind::SaveConfig,
     parseFile},
    {{"colormap", "3d|mpr|overlay|functional NAME",
      "a colour map chooser (NAME: grey, grey-inverted, hot-iron, pet, hot-metal-blue, "
      "pet-20-step, hot-metal); functional: the PET/CT layout's functional pane and MIP",
      "colormap functional hot-iron"},
     Kind::Colormap,
     parseColormap},
    {{"layout", "NAME",
      "standard, pet-ct (axial), pet-ct-coronal, pet-ct-sagittal (key L cycles them)",
      "layout pet-ct-coronal"},
     Kind::Layout,
     parseLayout},
    {{"orbit", "spin|rock|off", "the rotating 3D view (keys O and K toggle it)", "orbit rock"},
     Kind::Orbit,
     parseOrbit},
    {{"glyph-label", "N KIND|none",
      "what label N of a label map gets (the panel's picker; KIND: bumps, dimples, rings, "
      "ridges, cones, crosses)",
      "glyph-label 2 rings"},
     Kind::GlyphLabel,
     parseGlyphLabel},
    {{"register", "", "re-run the registration in the background, as the study asks", "register"},
     Kind::Register,
     nullptr},
    {{"wait-registration", "", "wait until the registration's re-run has ended",
      "wait-registration"},
     Kind::WaitRegistration,
     nullptr},
    {{"roi", "PANE x0 y0 x1 y1",
      "a sphere ROI drawn by a drag on an MPR pane: centre at (x0, y0) on the pane's plane, "
      "radius the distance to (x1, y1)",
      "roi axial 0.5 0.5 0.6 0.5"},
     Kind::Roi,
     parseDragOnMpr},
    {{"ruler", "PANE x0 y0 x1 y1", "a distance ruler on an MPR pane from (x0, y0) to (x1, y1)",
      "ruler coronal 0.2 0.5 0.8 0.5"},
     Kind::Ruler,
     parseDragOnMpr},
    {{"sphere", "L P S R",
      "a sphere ROI by its centre (LPS mm) and radius (mm); the crosshair goes to its centre",
      "sphere 10 -20 30 15"},
     Kind::Sphere,
     parseSphere},
    {{"roi-stats", "FILE", "every sphere's statistics, JSON (`mvw stats`'s fields)",
      "roi-stats out/roi.json"},
     Kind::RoiStats,
     parseFile},
    {{"clear-measurements", "", "no sphere, no ruler", "clear-measurements"},
     Kind::ClearMeasurements,
     nullptr},
    {{"pacs-server", "NAME",
      "the PACS window on the server of that name in servers.json (the rest of the line)",
      "pacs-server Clinic PACS"},
     Kind::PacsServer,
     parsePacsServer},
    {{"pacs-search", "[KEY=VALUE ...]",
      "a study search, waited for; KEY: patient-id, patient-name, study-date, modality, "
      "accession",
      "pacs-search patient-id=P1 modality=PT"},
     Kind::PacsSearch,
     parsePacsSearch},
    {{"pacs-study", "N|UID",
      "the N-th study found (1: the first) or the one of that Study Instance UID; its series "
      "asked for, waited for",
      "pacs-study 1"},
     Kind::PacsStudy,
     parsePacsStudy},
    {{"pacs-series", "ROLE SERIES|none",
      "the series ROLE (anatomical, functional, segmentation) takes: its UID, number, modality "
      "or description (the rest of the line)",
      "pacs-series functional PT"},
     Kind::PacsSeries,
     parsePacsSeries},
    {{"pacs-registration", "none|rigid|affine", "the registration rule of the study opened",
      "pacs-registration rigid"},
     Kind::PacsRegistration,
     parsePacsRegistration},
    {{"pacs-open", "[nowait]",
      "retrieve and open the chosen series as the study shown; waits until it is open or has "
      "failed (the panel says why, and the current study stays); nowait: goes on while it runs",
      "pacs-open nowait"},
     Kind::PacsOpen,
     parsePacsOpen},
    {{"pacs-wait", "[progress]",
      "wait for the PACS window's running step (search, series, open) to end; progress: only "
      "until its retrieve has received an instance",
      "pacs-wait progress"},
     Kind::PacsWait,
     parsePacsWait},
    {{"pacs-report", "FILE",
      "the PACS window's state, JSON: server, studies, series, chosen series, status, error",
      "pacs-report out/pacs.json"},
     Kind::PacsReport,
     parseFile},
    {{"quit", "", "close the window", "quit"}, Kind::Quit, nullptr},
};

Command parseLine(const std::string& text, const std::filesystem::path& source, int number) {
  LineReader in(text, source, number);
  Command c;
  c.line = number;
  if (in.empty()) return c;
  const std::string cmd = in.word("command");
  if (cmd[0] == '#') return c;
  const auto entry = std::find_if(std::begin(kCommands), std::end(kCommands),
                                  [&](const Entry& e) { return cmd == e.info.name; });
  if (entry == std::end(kCommands)) in.fail("unknown command '" + cmd + "'");
  c.kind = entry->kind;
  if (entry->parse) entry->parse(in, c);
  in.end();
  return c;
}

// A Markdown table cell: '|' would end it.
std::string cell(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

}  // namespace

std::vector<ViewerScript::CommandInfo> ViewerScript::commandInfo() {
  std::vector<CommandInfo> out;
  for (const Entry& e : kCommands) out.push_back(e.info);
  return out;
}

std::string ViewerScript::reference() {
  std::string md =
      "<!-- Generated by `mvw view --script-reference` from the command table in "
      "modules/viewer/src/ViewerScript.cpp: edit the table there and regenerate "
      "(scripts/script-reference), rather than editing this table. -->\n"
      "| command | what it does | example |\n"
      "|---|---|---|\n";
  for (const Entry& e : kCommands) {
    const std::string usage =
        std::string(e.info.name) + (*e.info.arguments ? " " : "") + e.info.arguments;
    md +=
        "| `" + cell(usage) + "` | " + cell(e.info.help) + " | `" + cell(e.info.example) + "` |\n";
  }
  md += "<!-- End of the generated script reference. -->\n";
  return md;
}

ViewerScript ViewerScript::parse(const std::string& text, const std::filesystem::path& source) {
  ViewerScript script;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);)
    script.commands_.push_back(parseLine(line, source, ++number));
  script.source_ = source;
  return script;
}

ViewerScript ViewerScript::load(const std::filesystem::path& file) {
  requireReadable(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot read the script");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file);
}

void ViewerScript::dragIncrement(ViewerState& state) {
  const Command& d = commands_[*dragging_];
  --dragFramesLeft_;
  state.drag(d.pane, d.x / d.frames, d.y / d.frames, d.button, false);
  state.requests().setScriptedInteraction(true);
}

bool ViewerScript::step(ViewerState* statePointer, PacsBrowser* pacs) {
  if (waitingPacs_) {
    // The search, the series or the open still runs (or, for pacs-wait progress, its retrieve
    // has received nothing yet).
    if (pacs && pacs->busy() && !(waitingProgress_ && pacs->retrieving())) return true;
    waitingPacs_ = waitingProgress_ = false;
  }
  if (next_ < commands_.size() && commands_[next_].kind >= Kind::PacsServer &&
      commands_[next_].kind <= Kind::PacsReport) {
    runPacs(commands_[next_++], pacs);
    return true;
  }
  if (!statePointer) {  // no study open: waits, screenshots, the PACS and quit only
    if (wait_ > 0) return --wait_, true;
    if (next_ >= commands_.size()) return false;
    const Command& c = commands_[next_++];
    if (c.kind == Kind::Wait) wait_ = c.frames;
    if (c.kind == Kind::Quit) return false;
    if (c.kind == Kind::Screenshot) idleRequests_.requestScreenshot(c.file);
    if (c.kind != Kind::Nothing && c.kind != Kind::Wait && c.kind != Kind::Screenshot)
      scriptError(source_, c.line, "no study is open (open one from the PACS first)");
    return true;
  }
  ViewerState& state = *statePointer;
  if (dragging_) {
    // One increment per drawn frame, every frame of it interactive; the frame after the last
    // increment's is not, so the pane refines at full resolution as after a real drag.
    if (dragFramesLeft_ > 0) {
      dragIncrement(state);
      return true;
    }
    dragging_.reset();
    state.requests().setScriptedInteraction(false);
  }
  if (wait_ > 0) {
    --wait_;
    return true;
  }
  if (next_ >= commands_.size()) return false;
  const Command& c = commands_[next_++];
  switch (c.kind) {
    case Kind::Nothing:
      break;
    case Kind::Key:
      state.key(c.key, c.ctrl);
      break;
    case Kind::Drag:
      state.drag(c.pane, c.x, c.y, c.button, false);
      break;
    case Kind::DragFrames:
      dragging_ = next_ - 1;
      dragFramesLeft_ = c.frames;
      dragIncrement(state);
      break;
    case Kind::Click:
      state.click(c.pane, c.x, c.y);
      break;
    case Kind::Wheel:
      state.wheel(c.pane, c.x, c.ctrl);
      break;
    case Kind::Jump:
      state.jumpNext();
      break;
    case Kind::Iso:
      state.view3d().iso = c.x;
      state.markAllDirty();
      break;
    case Kind::Maximise:
      state.toggleMaximised(c.pane);
      break;
    case Kind::Zoom:
      state.zoomPane(c.pane, c.x);
      break;
    case Kind::Pan:
      state.panPane(c.pane, c.x, c.y);
      break;
    case Kind::Wait:
      wait_ = c.frames;
      break;
    case Kind::Screenshot:
      state.requests().requestScreenshot(c.file);
      break;
    case Kind::PaneScreenshot:
      state.requests().requestPaneScreenshot(c.pane, c.file);
      break;
    case Kind::SaveConfig:
      state.saveConfig(c.file);
      break;
    case Kind::Dump:
      state.dump(c.pane, c.file);
      break;
    case Kind::PaneReport:
      writePaneReport(state, c.file);
      break;
    case Kind::Colormap:
      state.setColormap(c.target, c.colormap);
      break;
    case Kind::Orbit:
      state.setOrbit(c.orbit);
      break;
    case Kind::Layout:
      state.setLayout(c.layout);
      break;
    case Kind::GlyphLabel:
      state.setGlyphLabel(c.label, c.labelKind);
      break;
    case Kind::Register:
      state.registration().start();
      break;
    case Kind::WaitRegistration:
      if (state.registration().running()) --next_;  // stay on this line until the worker is done
      break;
    case Kind::Roi:
    case Kind::Ruler:
      state.measurements().beginGesture(
          c.pane, c.kind == Kind::Roi ? MprTool::Sphere : MprTool::Ruler, c.x, c.y);
      state.measurements().moveGesture(c.x1, c.y1);
      state.measurements().endGesture();
      break;
    case Kind::Hover:
      state.setCursor(c.pane, c.x, c.y);
      break;
    case Kind::Sphere:
      state.measurements().addSphere(c.sphere);
      state.setCrosshair({c.sphere.centre[0], c.sphere.centre[1], c.sphere.centre[2]});
      break;
    case Kind::RoiStats:
      state.measurements().writeSphereStatistics(c.file);
      break;
    case Kind::ClearMeasurements:
      state.measurements().clear();
      break;
    case Kind::PacsServer:
    case Kind::PacsSearch:
    case Kind::PacsStudy:
    case Kind::PacsSeries:
    case Kind::PacsRegistration:
    case Kind::PacsOpen:
    case Kind::PacsWait:
    case Kind::PacsReport:
      break;  // run above, with or without a study
    case Kind::Quit:
      state.requests().requestQuit();
      break;
  }
  return true;
}

void ViewerScript::runPacs(const Command& c, PacsBrowser* pacs) {
  auto fail = [&](const std::string& problem) { scriptError(source_, c.line, problem); };
  if (!pacs) fail("the PACS commands need the viewer's PACS panel");
  if (c.kind != Kind::PacsReport && c.kind != Kind::PacsWait)
    pacs->requestWindow();  // what the script does, on screen
  try {
    switch (c.kind) {
      case Kind::PacsServer:
        if (!pacs->selectServer(c.text)) {
          std::string names;
          for (const PacsServerEntry& s : pacs->servers())
            names += (names.empty() ? "" : ", ") + s.name;
          fail("pacs-server: no server named '" + c.text + "' in " + pacs->serversFile().string() +
               " (" + (names.empty() ? "none" : names) + ")");
        }
        break;
      case Kind::PacsSearch:
        if (pacs->server() < 0) fail("pacs-search: no server chosen (pacs-server NAME)");
        pacs->query() = c.query;
        pacs->search();
        waitingPacs_ = true;
        break;
      case Kind::PacsStudy: {
        const auto& studies = pacs->studies();
        int index = -1;
        for (std::size_t i = 0; i < studies.size(); ++i) {
          const auto it = studies[i].find("StudyInstanceUID");
          if (it != studies[i].end() && it->second == c.text) index = static_cast<int>(i);
        }
        if (index < 0 && !c.text.empty() &&
            c.text.find_first_not_of("0123456789") == std::string::npos && c.text.size() < 6)
          index = std::stoi(c.text) - 1;
        if (index < 0 || index >= static_cast<int>(studies.size()))
          fail("pacs-study: no study '" + c.text + "' among the " + std::to_string(studies.size()) +
               " found");
        pacs->chooseStudy(index);
        waitingPacs_ = true;
        break;
      }
      case Kind::PacsSeries:
        if (c.text == "none")
          pacs->setSeries(c.role, "");
        else
          pacs->chooseSeries(c.role, c.text);
        break;
      case Kind::PacsRegistration:
        pacs->registration = c.registration;
        break;
      case Kind::PacsOpen:
        pacs->open();
        waitingPacs_ = c.frames != -1;
        break;
      case Kind::PacsWait:
        waitingPacs_ = true;
        waitingProgress_ = c.frames == -1;
        break;
      case Kind::PacsReport:
        pacs->writeReport(c.file);
        break;
      default:
        break;
    }
  } catch (const InputError& e) {
    if (e.file() == source_) throw;
    fail(std::string(e.what()));
  }
}

}  // namespace mvw::viewer
