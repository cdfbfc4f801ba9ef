#include "ViewCommand.h"

#include <iostream>
#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "Viewer.h"
#include "mvw/viewer/ViewerLaunch.h"
#include "mvw/viewer/ViewerScript.h"

namespace mvw::app {

namespace {

struct ViewOptions {
  std::string study, anatomical, functional, script, frameLog, servers;
  int width = 1400, height = 900;
  double uiScale = 1.0;
  bool scriptReference = false;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

void runView(const ViewOptions& o) {
  if (o.scriptReference) {
    std::cout << viewer::ViewerScript::reference() << std::flush;
    return;
  }
  ViewerOptions v;
  v.launch = viewer::launchViewer({o.study, o.anatomical, o.functional, o.servers}, o.pacs);
  v.pacs = o.pacs;
  v.script = o.script;
  v.frameLog = o.frameLog;
  v.width = o.width;
  v.height = o.height;
  v.uiScale = o.uiScale;
  runViewer(std::move(v));
}

}  // namespace

void addViewCommand(CLI::App& app, const pacs::Options& pacs) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Interactive viewer: 3D view + axial, coronal, sagittal MPR with a linked crosshair.\n"
      "Mouse: 3D left-drag rotate, right-drag zoom, middle-drag pan, wheel zoom; MPR left "
      "click/drag moves the\n"
      "crosshair, wheel scrolls slices, Ctrl+wheel zooms, middle-drag pans (the MPR panes "
      "together),\nright-drag or Ctrl-drag window/level, Shift-drag a sphere "
      "ROI, Alt-drag a ruler (or the panel's MPR mouse tool);\ndouble-click maximises a view.\n"
      "Keys: 1 composite, 2 isosurface, 3 MIP, 4 MinIP, 5 average, D depth cue, G glyphs, F colour "
      "fusion,\n"
      "P next preset, Z fit the MPR panes, C centre them on the crosshair, J jump\n(hottest voxel, "
      "segments, ROIs), X one pixel per voxel, "
      "R reset, S screenshot, "
      "Ctrl+S save the state\nas a study config (mvw render reproduces it).");
  cmd->add_option("study", o->study, "Study config (.json)");
  cmd->add_option("--anatomical", o->anatomical,
                  "Anatomical volume (DICOM folder or file, NIfTI, MetaImage)");
  cmd->add_option("--functional", o->functional, "Functional volume");
  cmd->add_option("--script", o->script,
                  "Scripted events, one per line (tests; --script-reference lists the commands)");
  cmd->add_flag("--script-reference", o->scriptReference,
                "Print the --script commands as Markdown, as docs/user-guide/view.md has them, "
                "and exit");
  cmd->add_option("--servers", o->servers,
                  "PACS servers for the PACS window, JSON (default "
                  "$XDG_CONFIG_HOME/mvw/servers.json; docs/user-guide/pacs.md)");
  cmd->add_option("--frame-log", o->frameLog,
                  "Write one CSV line per drawn frame: its time, the 3D pane's render time and "
                  "size, whether it was a drag frame (benchmarks of interactivity)");
  cmd->add_option("--width", o->width, "Window width")->check(CLI::Range(640, 8192));
  cmd->add_option("--height", o->height, "Window height")->check(CLI::Range(480, 8192));
  cmd->add_option("--ui-scale", o->uiScale,
                  "Panel text and controls scaled (1.5 for a high-density screen)")
      ->check(CLI::Range(0.5, 4.0));
  cmd->callback([o, &pacs] {
    o->pacs = pacs;
    runView(*o);
  });
}

}  // namespace mvw::app
