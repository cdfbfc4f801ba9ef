#include "RenderCommand.h"

#include "CliChecks.h"
#include "DicomOutput.h"
#include "HeadlessGl.h"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/core/Error.h"
#include "mvw/output/StudyRender.h"

namespace mvw::app {

namespace {

struct RenderOptions {
  std::string study;
  std::string outDir;
  mvw::study::ViewOverrides overrides;
  std::vector<std::string> onlyViews;
  std::string gl;  // --gl (empty: MVW_GL, else auto)
  std::string gradient = "auto";
  DicomOutputOptions dicom;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

void runRender(const RenderOptions& o) {
  checkDicomOutput(o.dicom, o.dicom.dicom, o.outDir);
  output::RenderRequest request;
  request.study = o.study;
  request.outDir = o.outDir;
  request.overrides = o.overrides;
  request.onlyViews = o.onlyViews;
  request.gl = o.gl;
  request.gradient = o.gradient;
  request.dicom = o.dicom.dicom;
  request.given = o.dicom.given();
  request.pacs = o.pacs;
  const output::RenderedStudy rendered = output::renderStudy(request, std::cout, std::cerr);
  if (o.dicom.dicom) storeDicom(o.dicom, o.pacs, rendered.dicomFiles, o.outDir, std::cout);
}

}  // namespace

void addRenderCommand(CLI::App& app, const pacs::Options& pacs) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render the views of a study config headless (EGL or OSMesa) to PNG + render.json");
  cmd->add_option("study", o->study, "Study config (.json)")->required();
  cmd->add_option("-o,--output", o->outDir, "Output folder")->required();
  cmd->add_option("--only-view", o->onlyViews,
                  "Render only the view of this name (repeat for several); --view is a camera "
                  "direction")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--mode", o->overrides.mode,
                  "composite | isosurface | mip | minip | average | mpr | shells-mip | shells-sum "
                  "| shells-lit");
  cmd->add_option("--view", o->overrides.view,
                  "anterior | posterior | left | right | superior | inferior (MPR: axial | coronal "
                  "| sagittal)");
  cmd->add_option("--preset", o->overrides.preset,
                  "Transfer function: ct-bone, ct-skin, ct-muscle-bone, mr-default, pet-hot-metal");
  cmd->add_option("--size", o->overrides.size, "Image width and height in pixels")
      ->check(CLI::Range(1, 8192));
  cmd->add_option("--azimuth", o->overrides.azimuth, "Degrees about the view's up axis");
  cmd->add_option("--elevation", o->overrides.elevation, "Degrees about the view's right axis");
  cmd->add_option("--roll", o->overrides.roll, "Degrees about the line of sight");
  cmd->add_option("--zoom", o->overrides.zoom, "Magnification (1 fits the volume)")
      ->check(positive());
  cmd->add_option("--window", o->overrides.window, "Window width for projections")
      ->check(positive());
  cmd->add_option("--level", o->overrides.level, "Window centre for projections");
  cmd->add_option("--iso", o->overrides.iso, "Isosurface value");
  cmd->add_option("--sampling", o->overrides.sampling, "linear | nearest");
  cmd->add_option("--cue-brightness", o->overrides.cueBrightness,
                  "MIP depth cue: brightness beta0 (Heidrich 1995)");
  cmd->add_option("--cue-amount", o->overrides.cueAmount, "MIP depth cue: amount a (0 = none)");
  cmd->add_option("--cue-contrast", o->overrides.cueContrast,
                  "MIP depth cue: contrast b (1 = plain MIP)");
  cmd->add_option("--colormap", o->overrides.colormap,
                  "Colour map of mip, minip, average and mpr views: grey | grey-inverted | "
                  "hot-iron | pet | hot-metal-blue | pet-20-step | hot-metal");
  cmd->add_option("--overlay-colormap", o->overrides.overlayColormap,
                  "Colour map of the functional overlay and fusion (default hot-metal)");
  cmd->add_option("--orbit", o->overrides.orbit,
                  "Rotating view: N frames (2..720) about the patient's long axis, written as "
                  "VIEW/frame-000.png ... and VIEW.mp4");
  cmd->add_option("--orbit-mode", o->overrides.orbitMode,
                  "spin (a full turn) | rock (back and forth over +-orbit_range, default 30 deg)");
  cmd->add_flag("--perspective", o->overrides.perspective,
                "Perspective instead of orthographic projection");
  cmd->add_flag("--no-annotate", o->overrides.noAnnotate,
                "No orientation labels, scale bar or caption");
  addGlOption(*cmd, o->gl);
  addGradientOption(*cmd, o->gradient);
  addDicomOptions(*cmd, o->dicom, true);
  cmd->callback([o, &pacs] {
    if (o->overrides.window.has_value() != o->overrides.level.has_value())
      throw InputError(o->study, "--window and --level go together");
    o->pacs = pacs;
    runRender(*o);
  });
}

}  // namespace mvw::app
