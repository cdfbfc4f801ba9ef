#include "mvw/viewer/ViewerScript.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "mvw/core/Error.h"
#include "mvw/core/GlyphDefaults.h"

namespace mvw::viewer {

namespace {

using Command = ViewerScript::Command;
using Kind = Command::Kind;

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
    throw InputError(source_, "line " + std::to_string(number_) + ": " + problem);
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

Command parseLine(const std::string& text, const std::filesystem::path& source, int number) {
  LineReader in(text, source, number);
  Command c;
  c.line = number;
  if (in.empty()) return c;
  const std::string cmd = in.word("command");
  if (cmd[0] == '#') return c;
  if (cmd == "key") {
    c.kind = Kind::Key;
    const std::string k = in.word("key");
    if (k.size() != 1)
      in.fail("key: '" + k + "' is not one key (1-5, d, g, f, p, r, s, o, k, z, x, c, j, l)");
    c.key = static_cast<char>(std::toupper(static_cast<unsigned char>(k[0])));
    if (in.more()) {
      const std::string mod = in.word("modifier");
      if (mod != "ctrl") in.fail("key: unknown modifier '" + mod + "' (ctrl)");
      c.ctrl = true;
    }
  } else if (cmd == "drag" || cmd == "drag-frames") {
    c.kind = cmd == "drag" ? Kind::Drag : Kind::DragFrames;
    c.pane = in.pane();
    c.x = in.number("dx");
    c.y = in.number("dy");
    if (c.kind == Kind::DragFrames) {
      const double frames = in.number("frame count");
      if (frames < 1 || frames != std::floor(frames) || frames > 1e5)
        in.fail("drag-frames: the frame count must be a whole number from 1 to 100000");
      c.frames = static_cast<int>(frames);
    }
    if (in.more()) {
      const std::string b = in.word("button");
      if (b == "left")
        c.button = MouseButton::Left;
      else if (b == "right")
        c.button = MouseButton::Right;
      else if (b == "middle")
        c.button = MouseButton::Middle;
      else
        in.fail(cmd + ": unknown button '" + b + "' (left, right, middle)");
    }
  } else if (cmd == "click") {
    c.kind = Kind::Click;
    c.pane = in.pane();
    c.x = in.number("x");
    c.y = in.number("y");
  } else if (cmd == "wheel") {
    c.kind = Kind::Wheel;
    c.pane = in.pane();
    c.x = in.number("notches");
    if (in.more()) {
      const std::string mod = in.word("modifier");
      if (mod != "ctrl") in.fail("wheel: unknown modifier '" + mod + "' (ctrl)");
      c.ctrl = true;
    }
  } else if (cmd == "jump") {
    c.kind = Kind::Jump;
  } else if (cmd == "iso") {
    c.kind = Kind::Iso;
    c.x = in.number("value");
  } else if (cmd == "zoom") {
    c.kind = Kind::Zoom;
    c.pane = in.pane();
    c.x = in.number("factor");
    if (!(c.x >= 0.01 && c.x <= 100)) in.fail("zoom: the factor must lie in 0.01 .. 100");
  } else if (cmd == "pan") {
    c.kind = Kind::Pan;
    c.pane = in.pane();
    c.x = in.number("dx");
    c.y = in.number("dy");
    if (!(std::abs(c.x) <= 1e5 && std::abs(c.y) <= 1e5)) in.fail("pan: dx and dy within +-1e5 mm");
  } else if (cmd == "wait") {
    c.kind = Kind::Wait;
    const double frames = in.number("frame count");
    if (frames < 0 || frames != std::floor(frames) || frames > 1e6)
      in.fail("wait: the frame count must be a whole number from 0 to 1000000");
    c.frames = static_cast<int>(frames);
  } else if (cmd == "screenshot" || cmd == "save-config") {
    c.kind = cmd == "screenshot" ? Kind::Screenshot : Kind::SaveConfig;
    c.file = in.word("file");
  } else if (cmd == "screenshot-pane") {
    c.kind = Kind::PaneScreenshot;
    c.pane = in.pane();
    c.file = in.word("file");
  } else if (cmd == "dump") {
    c.kind = Kind::Dump;
    c.pane = in.pane();
    c.file = in.word("file");
  } else if (cmd == "colormap") {
    c.kind = Kind::Colormap;
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
  } else if (cmd == "layout") {
    c.kind = Kind::Layout;
    const std::string name = in.word("layout");
    const std::optional<config::ViewerLayout> layout = config::parseViewerLayout(name);
    if (!layout)
      in.fail("layout: unknown layout '" + name + "' (" + config::viewerLayoutList() + ")");
    c.layout = *layout;
  } else if (cmd == "orbit") {
    c.kind = Kind::Orbit;
    const std::string mode = in.word("mode");
    if (mode == "spin")
      c.orbit = Orbit::Spin;
    else if (mode == "rock")
      c.orbit = Orbit::Rock;
    else if (mode == "off")
      c.orbit = Orbit::Off;
    else
      in.fail("orbit: unknown mode '" + mode + "' (spin, rock, off)");
  } else if (cmd == "glyph-label") {
    c.kind = Kind::GlyphLabel;
    const double label = in.number("label");
    if (label < 1 || label != std::floor(label) || label > kMaxGlyphLabel)
      in.fail("glyph-label: the label must be a whole number from 1 to " +
              std::to_string(kMaxGlyphLabel));
    c.label = static_cast<int>(label);
    const std::string kind = in.word("kind");
    const std::optional<config::LabelGlyphKind> k = config::parseLabelGlyphKind(kind);
    if (!k)
      in.fail("glyph-label: unknown kind '" + kind +
              "' (bumps, dimples, rings, ridges, cones, crosses, none)");
    c.labelKind = *k;
  } else if (cmd == "register") {
    c.kind = Kind::Register;
  } else if (cmd == "wait-registration") {
    c.kind = Kind::WaitRegistration;
  } else if (cmd == "roi" || cmd == "ruler") {
    c.kind = cmd == "roi" ? Kind::Roi : Kind::Ruler;
    c.pane = in.pane();
    if (c.pane == k3d) in.fail(cmd + ": draws on an MPR pane (axial, coronal, sagittal)");
    c.x = in.number("x0");
    c.y = in.number("y0");
    c.x1 = in.number("x1");
    c.y1 = in.number("y1");
  } else if (cmd == "hover") {
    c.kind = Kind::Hover;
    c.pane = in.pane();
    if (c.pane == k3d) in.fail("hover: reads values on an MPR pane (axial, coronal, sagittal)");
    c.x = in.number("x");
    c.y = in.number("y");
  } else if (cmd == "sphere") {
    c.kind = Kind::Sphere;
    for (double& v : c.sphere.centre) v = in.number("centre (L P S mm)");
    c.sphere.radiusMm = in.number("radius");
    if (!(c.sphere.radiusMm > 0)) in.fail("sphere: the radius must be above 0 mm");
  } else if (cmd == "roi-stats") {
    c.kind = Kind::RoiStats;
    c.file = in.word("file");
  } else if (cmd == "clear-measurements") {
    c.kind = Kind::ClearMeasurements;
  } else if (cmd == "pacs-server") {
    c.kind = Kind::PacsServer;
    c.text = in.rest("server name");
  } else if (cmd == "pacs-search") {
    c.kind = Kind::PacsSearch;
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
  } else if (cmd == "pacs-study") {
    c.kind = Kind::PacsStudy;
    c.text = in.word("study (N or UID)");
  } else if (cmd == "pacs-series") {
    c.kind = Kind::PacsSeries;
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
  } else if (cmd == "pacs-registration") {
    c.kind = Kind::PacsRegistration;
    const std::string method = in.word("method");
    if (method == "none")
      c.registration = config::RegistrationMethod::None;
    else if (method == "rigid")
      c.registration = config::RegistrationMethod::Rigid;
    else if (method == "affine")
      c.registration = config::RegistrationMethod::Affine;
    else
      in.fail("pacs-registration: unknown method '" + method + "' (none, rigid, affine)");
  } else if (cmd == "pacs-open") {
    c.kind = Kind::PacsOpen;
    if (in.more()) {
      const std::string how = in.word("nowait");
      if (how != "nowait") in.fail("pacs-open: unknown option '" + how + "' (nowait)");
      c.frames = -1;  // not waited for
    }
  } else if (cmd == "pacs-wait") {
    c.kind = Kind::PacsWait;
    if (in.more()) {
      const std::string what = in.word("progress");
      if (what != "progress") in.fail("pacs-wait: unknown option '" + what + "' (progress)");
      c.frames = -1;
    }
  } else if (cmd == "pacs-report") {
    c.kind = Kind::PacsReport;
    c.file = in.word("file");
  } else if (cmd == "quit") {
    c.kind = Kind::Quit;
  } else {
    in.fail("unknown command '" + cmd + "'");
  }
  in.end();
  return c;
}

}  // namespace

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
      throw InputError(source_, "line " + std::to_string(c.line) +
                                    ": no study is open (open one from the PACS first)");
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
      state.view3d().isoValue = c.x;
      state.markAllDirty();
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
  const std::string where = "line " + std::to_string(c.line) + ": ";
  auto fail = [&](const std::string& problem) { throw InputError(source_, where + problem); };
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
