// The viewer's --script: every command the Xvfb test uses parses and acts on the state, and a
// malformed script is bad input named by file and line before any window opens.
#include "mvw/viewer/ViewerScript.h"

#include <atomic>
#include <chrono>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestUtil.h"
#include "mvw/config/StudyConfig.h"
#include "mvw/core/ColorMap.h"
#include "mvw/core/Error.h"
#include "mvw/core/GlyphDefaults.h"

namespace mvw::viewer {
namespace {

using Kind = ViewerScript::Command::Kind;

// The problem InputError reports for `text`, or "" when it parses.
std::string problemOf(const std::string& text) {
  try {
    ViewerScript::parse(text, "test.script");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), std::filesystem::path("test.script"));
    return e.problem();
  }
  return "";
}

TEST(ViewerScript, ParsesEveryCommand) {
  const ViewerScript s = ViewerScript::parse(
      "wait 2\n"
      "screenshot out/composite.png\n"
      "key 3\n"
      "key s ctrl\n"
      "drag 3d 0.15 0.05\n"
      "drag axial -0.5 1e-2 right\n"
      "click axial 0.55 0.45\n"
      "wheel coronal 4\n"
      "\n"
      "# a comment\n"
      "dump 3d out/window-3d.png\n"
      "save-config out/saved.json\n"
      "register\n"
      "wait-registration\n"
      "quit\n",
      "test.script");
  const auto& c = s.commands();
  ASSERT_EQ(c.size(), 15u);
  EXPECT_EQ(c[0].kind, Kind::Wait);
  EXPECT_EQ(c[0].frames, 2);
  EXPECT_EQ(c[1].kind, Kind::Screenshot);
  EXPECT_EQ(c[1].file, std::filesystem::path("out/composite.png"));
  EXPECT_EQ(c[2].kind, Kind::Key);
  EXPECT_EQ(c[2].key, '3');
  EXPECT_FALSE(c[2].ctrl);
  EXPECT_EQ(c[3].key, 'S');  // keys are as typed: upper case, like GLFW's key codes
  EXPECT_TRUE(c[3].ctrl);
  EXPECT_EQ(c[4].kind, Kind::Drag);
  EXPECT_EQ(c[4].pane, k3d);
  EXPECT_DOUBLE_EQ(c[4].x, 0.15);
  EXPECT_DOUBLE_EQ(c[4].y, 0.05);
  EXPECT_EQ(c[4].button, MouseButton::Left);
  EXPECT_EQ(c[5].pane, kAxial);
  EXPECT_DOUBLE_EQ(c[5].x, -0.5);
  EXPECT_DOUBLE_EQ(c[5].y, 0.01);
  EXPECT_EQ(c[5].button, MouseButton::Right);
  EXPECT_EQ(c[6].kind, Kind::Click);
  EXPECT_EQ(c[7].kind, Kind::Wheel);
  EXPECT_EQ(c[7].pane, kCoronal);
  EXPECT_DOUBLE_EQ(c[7].x, 4.0);
  EXPECT_EQ(c[8].kind, Kind::Nothing);
  EXPECT_EQ(c[9].kind, Kind::Nothing);
  EXPECT_EQ(c[10].kind, Kind::Dump);
  EXPECT_EQ(c[10].pane, k3d);
  EXPECT_EQ(c[11].kind, Kind::SaveConfig);
  EXPECT_EQ(c[12].kind, Kind::Register);
  EXPECT_EQ(c[13].kind, Kind::WaitRegistration);
  EXPECT_EQ(c[14].kind, Kind::Quit);
  EXPECT_EQ(c[14].line, 15);
}

// A pane as the window shows it: its rectangle of the framebuffer, taken after the frame.
TEST(ViewerScript, LayoutCommandNamesALayout) {
  const ViewerScript script =
      ViewerScript::parse("layout pet-ct-coronal\nclick fused 0.5 0.5\n", "s.txt");
  ASSERT_EQ(script.commands().size(), 2u);
  EXPECT_EQ(script.commands()[0].kind, ViewerScript::Command::Kind::Layout);
  EXPECT_EQ(script.commands()[0].layout, config::ViewerLayout::PetCtCoronal);
  EXPECT_EQ(script.commands()[1].pane, kSagittal);
  EXPECT_EQ(problemOf("layout grid"),
            "line 1: layout: unknown layout 'grid' (standard, pet-ct, pet-ct-coronal or "
            "pet-ct-sagittal)");
}

TEST(ViewerScript, ScreenshotPaneNamesThePaneAndTheFile) {
  const ViewerScript s = ViewerScript::parse("screenshot-pane sagittal out/s.png\n", "t.script");
  ASSERT_EQ(s.commands().size(), 1u);
  EXPECT_EQ(s.commands()[0].kind, Kind::PaneScreenshot);
  EXPECT_EQ(s.commands()[0].pane, kSagittal);
  EXPECT_EQ(s.commands()[0].file, std::filesystem::path("out/s.png"));
  EXPECT_EQ(problemOf("screenshot-pane axial"), "line 1: screenshot-pane: missing file");
  EXPECT_EQ(problemOf("screenshot-pane top a.png"),
            "line 1: unknown pane 'top' (3d, axial, coronal, sagittal; in the PET/CT layout also "
            "mip, anatomical, "
            "functional, fused)");
}

TEST(ViewerScript, BadLinesNameTheLineAndTheProblem) {
  EXPECT_EQ(problemOf("wait 1\nzoomm 3d 2\n"), "line 2: unknown command 'zoomm'");
  EXPECT_EQ(problemOf("zoom axial 0"), "line 1: zoom: the factor must lie in 0.01 .. 100");
  EXPECT_EQ(problemOf("zoom axial"), "line 1: zoom: missing factor");
  EXPECT_EQ(problemOf("pan coronal 3"), "line 1: pan: missing dy");
  EXPECT_EQ(problemOf("wheel axial 2 shift"), "line 1: wheel: unknown modifier 'shift' (ctrl)");
  EXPECT_EQ(problemOf("click oblique 0.5 0.5"),
            "line 1: unknown pane 'oblique' (3d, axial, coronal, sagittal; in the PET/CT layout "
            "also mip, anatomical, "
            "functional, fused)");
  EXPECT_EQ(problemOf("drag 3d 0.1"), "line 1: drag: missing dy");
  EXPECT_EQ(problemOf("drag 3d 0.1 x"), "line 1: drag: dy 'x' is not a number");
  EXPECT_EQ(problemOf("drag 3d 0.1 0.2 sideways"),
            "line 1: drag: unknown button 'sideways' (left, right, middle)");
  EXPECT_EQ(problemOf("wheel axial 2 3"), "line 1: wheel: unknown modifier '3' (ctrl)");
  EXPECT_EQ(problemOf("key"), "line 1: key: missing key");
  EXPECT_EQ(problemOf("key ctrl"),
            "line 1: key: 'ctrl' is not one key (1-5, d, g, f, p, r, s, o, k, z, x, c, j, l)");
  EXPECT_EQ(problemOf("key s shift"), "line 1: key: unknown modifier 'shift' (ctrl)");
  EXPECT_EQ(problemOf("wait -1"),
            "line 1: wait: the frame count must be a whole number from 0 to 1000000");
  EXPECT_EQ(problemOf("wait 1.5"),
            "line 1: wait: the frame count must be a whole number from 0 to 1000000");
  EXPECT_EQ(problemOf("screenshot"), "line 1: screenshot: missing file");
  EXPECT_EQ(problemOf("dump 3d"), "line 1: dump: missing file");
  EXPECT_EQ(problemOf("quit now"), "line 1: quit: unexpected 'now'");
  EXPECT_EQ(problemOf("click axial nan 0.5"), "line 1: click: x 'nan' is not a number");
  EXPECT_EQ(problemOf("  # indented comment\n\t\nquit"), "");
  EXPECT_EQ(problemOf("drag-frames 3d 0.5 0"), "line 1: drag-frames: missing frame count");
  EXPECT_EQ(problemOf("drag-frames 3d 0.5 0 0"),
            "line 1: drag-frames: the frame count must be a whole number from 1 to 100000");
  EXPECT_EQ(problemOf("drag-frames 3d 0.5 0 2.5"),
            "line 1: drag-frames: the frame count must be a whole number from 1 to 100000");
  EXPECT_EQ(problemOf("drag-frames 3d 0.5 0 4 up"),
            "line 1: drag-frames: unknown button 'up' (left, right, middle)");
}

// The rest of the commands' complaints, pinned word for word (scripts and their tests quote them).
TEST(ViewerScript, EveryCommandsComplaintsStayAsTheyWere) {
  EXPECT_EQ(problemOf("hover 3d 0.5 0.5"),
            "line 1: hover: reads values on an MPR pane (axial, coronal, sagittal)");
  EXPECT_EQ(problemOf("roi 3d 0 0 1 1"),
            "line 1: roi: draws on an MPR pane (axial, coronal, sagittal)");
  EXPECT_EQ(problemOf("ruler mip 0 0 1 1"),
            "line 1: ruler: draws on an MPR pane (axial, coronal, sagittal)");
  EXPECT_EQ(problemOf("ruler axial 0 0 1"), "line 1: ruler: missing y1");
  EXPECT_EQ(problemOf("sphere 1 2"), "line 1: sphere: missing centre (L P S mm)");
  EXPECT_EQ(problemOf("sphere 1 2 3 0"), "line 1: sphere: the radius must be above 0 mm");
  EXPECT_EQ(problemOf("iso"), "line 1: iso: missing value");
  EXPECT_EQ(problemOf("pan axial 1e6 0"), "line 1: pan: dx and dy within +-1e5 mm");
  EXPECT_EQ(problemOf("colormap 2d grey"),
            "line 1: colormap: unknown target '2d' (3d, mpr, overlay, functional)");
  EXPECT_EQ(problemOf("colormap mpr"), "line 1: colormap: missing colour map");
  EXPECT_EQ(problemOf("orbit wobble"), "line 1: orbit: unknown mode 'wobble' (spin, rock, off)");
  EXPECT_EQ(problemOf("glyph-label 0 bumps"),
            "line 1: glyph-label: the label must be a whole number from 1 to " +
                std::to_string(kMaxGlyphLabel));
  EXPECT_EQ(problemOf("glyph-label 3 spikes"),
            "line 1: glyph-label: unknown kind 'spikes' (bumps, dimples, rings, ridges, cones, "
            "crosses, none)");
  EXPECT_EQ(problemOf("register now"), "line 1: register: unexpected 'now'");
  EXPECT_EQ(problemOf("roi-stats"), "line 1: roi-stats: missing file");
  EXPECT_EQ(problemOf("pacs-server"), "line 1: pacs-server: missing server name");
  EXPECT_EQ(problemOf("pacs-search =x"), "line 1: pacs-search: '=x' is not KEY=VALUE");
  EXPECT_EQ(problemOf("pacs-search sex=F"),
            "line 1: pacs-search: unknown key 'sex' (patient-id, patient-name, study-date, "
            "modality, accession)");
  EXPECT_EQ(problemOf("pacs-study"), "line 1: pacs-study: missing study (N or UID)");
  EXPECT_EQ(problemOf("pacs-series dose 3"),
            "line 1: pacs-series: unknown role 'dose' (anatomical, functional, segmentation)");
  EXPECT_EQ(problemOf("pacs-series functional"),
            "line 1: pacs-series: missing series (UID, number, modality, description or none)");
  EXPECT_EQ(problemOf("pacs-registration bspline"),
            "line 1: pacs-registration: unknown method 'bspline' (none, rigid, affine)");
  EXPECT_EQ(problemOf("pacs-open later"), "line 1: pacs-open: unknown option 'later' (nowait)");
  EXPECT_EQ(problemOf("pacs-wait all"), "line 1: pacs-wait: unknown option 'all' (progress)");
  EXPECT_EQ(problemOf("pacs-open nowait now"), "line 1: pacs-open: unexpected 'now'");
}

// The command table: every command's documented example parses to that command, the names are
// unique, every kind has a command, and the reference's lists are the parser's.
TEST(ViewerScriptTable, EveryCommandParsesItsExample) {
  std::set<std::string> names;
  std::set<Kind> kinds;
  for (const ViewerScript::CommandInfo& info : ViewerScript::commandInfo()) {
    SCOPED_TRACE(info.name);
    EXPECT_TRUE(names.insert(info.name).second) << "named twice";
    const std::string example = info.example;
    EXPECT_EQ(example.substr(0, example.find(' ')), info.name);
    EXPECT_EQ(problemOf(example), "");
    const ViewerScript s = ViewerScript::parse(example, "t");
    ASSERT_EQ(s.commands().size(), 1u);
    EXPECT_NE(s.commands()[0].kind, Kind::Nothing);
    kinds.insert(s.commands()[0].kind);
    // A command whose arguments are not all optional complains without them.
    if (*info.arguments && *info.arguments != '[') {
      EXPECT_NE(problemOf(info.name).find("missing"), std::string::npos);
    }
  }
  EXPECT_EQ(kinds.size(), static_cast<std::size_t>(Kind::Quit))  // every kind but Nothing
      << "a command kind without an entry in the table";
}

TEST(ViewerScriptTable, ExamplesParseToWhatTheyName) {
  const auto line = [](const std::string& name) {
    for (const ViewerScript::CommandInfo& info : ViewerScript::commandInfo())
      if (info.name == name) return ViewerScript::parse(info.example, "t").commands().at(0);
    ADD_FAILURE() << name;
    return ViewerScript::Command{};
  };
  EXPECT_EQ(line("drag-frames").frames, 6);
  EXPECT_EQ(line("colormap").target, ColorTarget::Functional);
  EXPECT_EQ(line("colormap").colormap, ColorMap::HotIron);
  EXPECT_EQ(line("pacs-server").text, "Clinic PACS");
  EXPECT_EQ(line("pacs-search").query.modality, "PT");
  EXPECT_EQ(line("pacs-series").role, PacsBrowser::Role::Functional);
  EXPECT_EQ(line("pacs-open").frames, -1);
  EXPECT_DOUBLE_EQ(line("sphere").sphere.radiusMm, 15.0);
}

TEST(ViewerScriptTable, UnknownCommandsAreNamed) {
  EXPECT_EQ(problemOf("teleport axial"), "line 1: unknown command 'teleport'");
  EXPECT_EQ(problemOf("quit\n\nQuit"), "line 3: unknown command 'Quit'");  // names are exact
  EXPECT_EQ(problemOf("#comment\nkey"), "line 2: key: missing key");
}

// A control byte the script file holds reaches the message escaped (\xNN), never raw: the
// terminal or log showing the message is not cleared, recoloured or rung.
TEST(ViewerScriptTable, ControlBytesInMessagesAreEscaped) {
  EXPECT_EQ(problemOf("zoo\x1b[2Jm 3d 2"), "line 1: unknown command 'zoo\\x1b[2Jm'");
  EXPECT_EQ(problemOf("layout \x07quad"),
            "line 1: layout: unknown layout '\\x07quad' (" + config::viewerLayoutList() + ")");
  EXPECT_EQ(problemOf("zoom 3d 2\x7f"), "line 1: zoom: factor '2\\x7f' is not a number");
}

TEST(ViewerScriptTable, TheHelpListsWhatTheParserAccepts) {
  std::string colormap, layout;
  for (const ViewerScript::CommandInfo& info : ViewerScript::commandInfo()) {
    if (std::string(info.name) == "colormap") colormap = info.help;
    if (std::string(info.name) == "layout") layout = info.help;
  }
  const std::size_t from = colormap.find("(NAME: ") + 7;
  std::vector<std::string> maps;
  std::istringstream listed(colormap.substr(from, colormap.find(')', from) - from));
  for (std::string name; std::getline(listed, name, ',');)
    maps.push_back(name.substr(name[0] == ' '));
  EXPECT_EQ(maps, colorMapNames());
  std::string list = config::viewerLayoutList();  // "standard, pet-ct, ... or pet-ct-sagittal"
  for (std::size_t at; (at = list.find(" or ")) != std::string::npos;) list.replace(at, 4, ", ");
  std::istringstream names(list);
  for (std::string name; std::getline(names, name, ',');) {
    name.erase(0, name.find_first_not_of(' '));
    EXPECT_NE(layout.find(name), std::string::npos) << name;
    EXPECT_TRUE(config::parseViewerLayout(name)) << name;
  }
}

TEST(ViewerScriptTable, TheReferenceHasARowPerCommand) {
  const std::string md = ViewerScript::reference();
  EXPECT_EQ(md.rfind("<!-- Generated by `mvw view --script-reference`", 0), 0u);
  for (const ViewerScript::CommandInfo& info : ViewerScript::commandInfo())
    EXPECT_NE(md.find("\n| `" + std::string(info.name)), std::string::npos) << info.name;
  EXPECT_NE(md.find("| `drag PANE dx dy [left\\|right\\|middle]` |"), std::string::npos);
}

// docs/user-guide/view.md holds the reference as the table generates it now.
TEST(ViewerScriptTable, TheUserGuideIsCurrent) {
  const std::filesystem::path file =
      std::filesystem::path(MVW_SOURCE_DIR) / "docs" / "user-guide" / "view.md";
  std::ifstream in(file, std::ios::binary);
  ASSERT_TRUE(in) << file;
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str(), now = ViewerScript::reference();
  const std::string first = now.substr(0, now.find('\n') + 1);
  const std::string last = "<!-- End of the generated script reference. -->\n";
  const std::size_t begin = doc.find(first), end = doc.find(last);
  ASSERT_NE(begin, std::string::npos) << file << " has no generated script reference";
  ASSERT_NE(end, std::string::npos) << file << " has no end to its script reference";
  EXPECT_EQ(doc.substr(begin, end + last.size() - begin), now)
      << file << " is not what the command table says now: regenerate it with\n"
      << "  scripts/script-reference build/release/app/mvw\n"
      << "and commit it with the change to the table.";
}

// Zoom and pan for tests of the MPR panes (issue 36 item 1), run on the state.
TEST(ViewerScript, ZoomAndPanReachTheState) {
  const ViewerScript s =
      ViewerScript::parse("zoom axial 2.5\npan sagittal 3 -4\nwheel coronal 1 ctrl\n", "t.script");
  ASSERT_EQ(s.commands().size(), 3u);
  EXPECT_EQ(s.commands()[0].kind, ViewerScript::Command::Kind::Zoom);
  EXPECT_EQ(s.commands()[0].pane, kAxial);
  EXPECT_DOUBLE_EQ(s.commands()[0].x, 2.5);
  EXPECT_EQ(s.commands()[1].kind, ViewerScript::Command::Kind::Pan);
  EXPECT_DOUBLE_EQ(s.commands()[1].x, 3.0);
  EXPECT_DOUBLE_EQ(s.commands()[1].y, -4.0);
  EXPECT_TRUE(s.commands()[2].ctrl);
}

TEST(ViewerScript, MissingFileIsBadInput) {
  const auto file = test::scratchDir() / "no-such-script";
  try {
    ViewerScript::load(file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.problem(), "no such file or directory");
  }
}

TEST(ViewerScript, LoadReadsTheFile) {
  const auto file = test::scratchDir() / "script";
  std::ofstream(file) << "key 3\nquit\n";
  EXPECT_EQ(ViewerScript::load(file).commands().size(), 2u);
  EXPECT_TRUE(ViewerScript::parse("", file).empty());
}

class ViewerScriptRun : public ::testing::Test {
 protected:
  ViewerScriptRun() {
    ct.metadata().modality = "CT";
    scene.valueRange = {-1000.0, 2000.0};
  }
  config::StudyConfig study;
  Volume ct{{5, 5, 5}, 1, ScalarType::Int16, glm::dmat4(1.0)};
  ViewerScene scene;
};

TEST_F(ViewerScriptRun, OneLinePerFrameAndWaitsCountFrames) {
  ViewerState state(study, ct, nullptr, scene);
  ViewerScript s = ViewerScript::parse("# start\nwait 2\nkey 3\nscreenshot a.png\nquit\n", "t");
  EXPECT_TRUE(s.step(state));  // the comment
  EXPECT_TRUE(s.step(state));  // wait 2
  EXPECT_TRUE(s.step(state));
  EXPECT_TRUE(s.step(state));
  EXPECT_EQ(state.view3d().mode, render::RenderMode::Composite);
  EXPECT_TRUE(s.step(state));  // key 3
  EXPECT_EQ(state.view3d().mode, render::RenderMode::Mip);
  EXPECT_TRUE(s.step(state));
  EXPECT_EQ(state.requests().takeScreenshotRequest(), std::filesystem::path("a.png"));
  EXPECT_FALSE(state.requests().quitRequested());
  EXPECT_TRUE(s.step(state));
  EXPECT_TRUE(state.requests().quitRequested());
  EXPECT_FALSE(s.step(state));  // the end
}

// A drag spread over N frames: the same rotation in all as one `drag`, one increment per frame,
// every one of those frames interactive, and the frame after the last one not (it refines).
TEST_F(ViewerScriptRun, DragFramesSpreadsTheDragAndMarksItsFramesInteractive) {
  ViewerState state(study, ct, nullptr, scene);
  const double start = state.view3d().camera.azimuthDeg;
  ViewerScript s = ViewerScript::parse("drag-frames 3d 0.5 0 4\nkey 3\n", "t");
  for (int frame = 1; frame <= 4; ++frame) {
    EXPECT_TRUE(s.step(state));
    EXPECT_TRUE(state.requests().scriptedInteraction()) << "frame " << frame;
    EXPECT_NEAR(state.view3d().camera.azimuthDeg - start, 0.5 * 180.0 * frame / 4.0, 1e-9);
    EXPECT_EQ(state.view3d().mode, render::RenderMode::Composite);  // not yet the next line
  }
  EXPECT_TRUE(s.step(state));  // the drag ends, and the next line runs in the same step
  EXPECT_FALSE(state.requests().scriptedInteraction());
  EXPECT_NEAR(state.view3d().camera.azimuthDeg - start, 90.0, 1e-9);
  EXPECT_EQ(state.view3d().mode, render::RenderMode::Mip);
  EXPECT_FALSE(s.step(state));

  ViewerState plain(study, ct, nullptr, scene);
  ViewerScript one = ViewerScript::parse("drag 3d 0.5 0\n", "t");
  one.step(plain);
  EXPECT_FALSE(plain.requests().scriptedInteraction());
  EXPECT_NEAR(plain.view3d().camera.azimuthDeg - start, 90.0, 1e-9);
}

TEST_F(ViewerScriptRun, WaitRegistrationHoldsUntilTheWorkerEnds) {
  Volume pet = ct;
  ViewerState state(study, ct, &pet, scene);
  std::atomic<bool> release{false};
  state.registration().setJob([&release](std::stop_token stop) {
    while (!release && !stop.stop_requested())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return resampling::RegistrationResult{};
  });
  ViewerScript s = ViewerScript::parse("register\nwait-registration\nkey 2\n", "t");
  s.step(state);
  EXPECT_TRUE(state.registration().running());
  for (int frame = 0; frame < 5; ++frame) {
    s.step(state);
    state.finishRegistration();
  }
  EXPECT_EQ(state.view3d().mode, render::RenderMode::Composite);  // still waiting
  release = true;
  while (state.registration().running()) {
    state.finishRegistration();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  s.step(state);  // wait-registration passes
  s.step(state);
  EXPECT_EQ(state.view3d().mode, render::RenderMode::Isosurface);
}

}  // namespace
}  // namespace mvw::viewer

namespace mvw::viewer {
namespace {

TEST(ViewerScript, ColormapAndOrbitCommands) {
  const ViewerScript s = ViewerScript::parse(
      "colormap 3d grey-inverted\ncolormap mpr hot-iron\ncolormap overlay pet-20-step\n"
      "orbit spin\norbit rock\norbit off\n",
      "t");
  const auto& c = s.commands();
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0].kind, Kind::Colormap);
  EXPECT_EQ(c[0].target, ColorTarget::View3d);
  EXPECT_EQ(c[0].colormap, ColorMap::GreyInverted);
  EXPECT_EQ(c[1].target, ColorTarget::Mpr);
  EXPECT_EQ(c[1].colormap, ColorMap::HotIron);
  EXPECT_EQ(c[2].target, ColorTarget::Overlay);
  EXPECT_EQ(c[2].colormap, ColorMap::Pet20Step);
  EXPECT_EQ(c[3].kind, Kind::Orbit);
  EXPECT_EQ(c[3].orbit, Orbit::Spin);
  EXPECT_EQ(c[4].orbit, Orbit::Rock);
  EXPECT_EQ(c[5].orbit, Orbit::Off);
  EXPECT_EQ(problemOf("colormap 3d jet"),
            "line 1: colormap: unknown colour map 'jet' (grey, grey-inverted, hot-iron, pet, "
            "hot-metal-blue, pet-20-step, hot-metal)");
  EXPECT_EQ(problemOf("colormap left pet"),
            "line 1: colormap: unknown target 'left' (3d, mpr, overlay, functional)");
  EXPECT_EQ(problemOf("colormap 3d"), "line 1: colormap: missing colour map");
  EXPECT_EQ(problemOf("orbit"), "line 1: orbit: missing mode");
  EXPECT_EQ(problemOf("orbit tumble"), "line 1: orbit: unknown mode 'tumble' (spin, rock, off)");
  EXPECT_EQ(problemOf("orbit spin 36"), "line 1: orbit: unexpected '36'");
}

TEST(ViewerScript, MeasurementCommands) {
  const ViewerScript s = ViewerScript::parse(
      "roi axial 0.5 0.4 0.6 0.4\nruler coronal 0.1 0.2 0.3 0.4\nsphere -42.2 -224.2 -422.5 15\n"
      "roi-stats out.json\nclear-measurements\nhover sagittal 0.5 0.5\n",
      "t");
  const auto& c = s.commands();
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0].kind, Kind::Roi);
  EXPECT_EQ(c[0].pane, kAxial);
  EXPECT_EQ(c[0].x, 0.5);
  EXPECT_EQ(c[0].x1, 0.6);
  EXPECT_EQ(c[0].y1, 0.4);
  EXPECT_EQ(c[1].kind, Kind::Ruler);
  EXPECT_EQ(c[1].pane, kCoronal);
  EXPECT_EQ(c[2].kind, Kind::Sphere);
  EXPECT_EQ(c[2].sphere.centre[2], -422.5);
  EXPECT_EQ(c[2].sphere.radiusMm, 15);
  EXPECT_EQ(c[3].kind, Kind::RoiStats);
  EXPECT_EQ(c[3].file, "out.json");
  EXPECT_EQ(c[4].kind, Kind::ClearMeasurements);
  EXPECT_EQ(c[5].kind, Kind::Hover);
  EXPECT_EQ(c[5].pane, kSagittal);
  EXPECT_EQ(problemOf("roi 3d 0 0 1 1"),
            "line 1: roi: draws on an MPR pane (axial, coronal, sagittal)");
  EXPECT_EQ(problemOf("ruler axial 0 0 1"), "line 1: ruler: missing y1");
  EXPECT_EQ(problemOf("sphere 0 0 0 0"), "line 1: sphere: the radius must be above 0 mm");
  EXPECT_EQ(problemOf("sphere 0 0 x 2"), "line 1: sphere: centre (L P S mm) 'x' is not a number");
  EXPECT_EQ(problemOf("roi-stats"), "line 1: roi-stats: missing file");
  EXPECT_EQ(problemOf("hover 3d 0.5 0.5"),
            "line 1: hover: reads values on an MPR pane (axial, coronal, sagittal)");
}

TEST_F(ViewerScriptRun, SphereMovesTheCrosshairAndRoiStatsWritesItsStatistics) {
  const auto dir = test::scratchDir();
  ViewerState state(study, ct, nullptr, scene);
  ViewerScript s = ViewerScript::parse(
      "sphere 2 2 2 1.5\nroi-stats " + (dir / "stats.json").string() + "\nclear-measurements\n",
      "t");
  EXPECT_TRUE(s.step(state));
  ASSERT_EQ(state.measurements().all().spheres.size(), 1u);
  EXPECT_EQ(state.crosshair(), glm::dvec3(2.0, 2.0, 2.0));
  EXPECT_TRUE(s.step(state));
  std::ifstream in(dir / "stats.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["sphere"][3], 1.5);
  // Centres within 1.5 mm: the centre, its 6 face and 12 edge neighbours.
  EXPECT_EQ(j[0]["anatomical"]["voxels"], 19);
  EXPECT_TRUE(s.step(state));
  EXPECT_TRUE(state.measurements().all().spheres.empty());
}

TEST_F(ViewerScriptRun, ColormapAndOrbitActOnTheState) {
  ViewerState state(study, ct, nullptr, scene);
  ViewerScript s = ViewerScript::parse("colormap 3d hot-iron\norbit spin\n", "t");
  EXPECT_TRUE(s.step(state));
  EXPECT_EQ(state.colormap(ColorTarget::View3d), ColorMap::HotIron);
  EXPECT_TRUE(s.step(state));
  EXPECT_EQ(state.orbit().mode(), Orbit::Spin);
}

TEST(ViewerScriptGlyphLabel, BadLabelsAndKindsNameTheLine) {
  for (const char* line : {"glyph-label 0 bumps", "glyph-label 2.5 bumps", "glyph-label 3 spikes",
                           "glyph-label 3", "glyph-label 16384 none"}) {
    try {
      ViewerScript::parse(line, "s.txt");
      ADD_FAILURE() << line;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("line 1: glyph-label"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace mvw::viewer
