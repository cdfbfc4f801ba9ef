#include "ViewerScript.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "mvw/core/Error.h"
#include "mvw/core/GlyphDefaults.h"

namespace mvw::app {

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

bool ViewerScript::step(ViewerState& state) {
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
    case Kind::Quit:
      state.requests().requestQuit();
      break;
  }
  return true;
}

}  // namespace mvw::app
