#include "RenderCommand.h"

#include "HeadlessGl.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Version.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/PngWriter.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Caption.h"
#include "mvw/study/FunctionalPlacement.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string study;
  std::string outDir;
  mvw::study::ViewOverrides overrides;
  std::string gl;  // --gl (empty: MVW_GL, else auto)
};

std::string fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

void runRender(const RenderOptions& o) {
  const config::StudyConfig study = config::loadStudyConfig(o.study);
  std::vector<mvw::study::PlannedView> views = mvw::study::planViews(study, o.overrides);
  // The context before the volumes: a --gl this machine cannot give fails in milliseconds.
  auto context = makeHeadlessContext(o.gl);
  const Study volumes = mvw::study::loadStudy(study);
  const Volume& anatomy = volumes.anatomical;
  const std::optional<Volume>& functional = volumes.functional;

  render::VolumeRenderer renderer(*context, anatomy);
  // The study's "registration" places the functional volume (none: by world coordinates).
  std::optional<mvw::study::FunctionalPlacement> placement;
  if (functional) {
    placement = mvw::study::placeFunctional(study, anatomy, *functional);
    renderer.setFunctional(*functional, placement->anatomicalFromFunctional);
  }
  const auto [lo, hi] = renderer.valueRange();
  struct Output {
    std::string file;
    Image image;
    nlohmann::json record;
  };
  std::vector<Output> outputs;
  for (auto& v : views) {
    mvw::study::applyDefaultPreset(v, anatomy);
    if (functional)
      mvw::study::applyAttributeDefaults(v, study.functionalKind, *functional,
                                         renderer.functionalRange());
    render::Frame frame = renderer.render(v.settings);
    const WindowLevel shown = windowOrFullRange(v.settings.window, v.settings.level, lo, hi);
    const std::string caption = mvw::study::viewCaption(v, shown);
    const bool shellMode = isShellMode(v.settings.mode);
    const bool overlayShown =
        functional &&
        (v.settings.mode == render::RenderMode::Mpr ? v.settings.overlay : v.settings.fusion);
    if (v.config.annotate) {
      render::annotate(frame.image, frame.camera, caption);
      if (overlayShown) {
        auto [flo, fhi] = renderer.functionalRange();
        if (v.settings.functionalHigh > v.settings.functionalLow)
          flo = v.settings.functionalLow, fhi = v.settings.functionalHigh;
        render::drawColourBar(frame.image, flo, fhi, functional->metadata().unit);
      }
    }
    nlohmann::json r;
    r["file"] = v.config.name + ".png";
    r["mode"] = toString(v.config.mode);
    r["view"] = config::toString(v.config.view);
    r["azimuth_deg"] = v.config.azimuth;
    r["elevation_deg"] = v.config.elevation;
    r["roll_deg"] = v.config.roll;
    r["zoom"] = v.config.zoom;
    r["perspective"] = v.config.perspective;
    r["size"] = {v.config.width, v.config.height};
    r["transfer_preset"] = v.presetName;
    if (v.settings.gradientOpacityHigh > 0)
      r["gradient_opacity"] = {v.settings.gradientOpacityLow, v.settings.gradientOpacityHigh};
    r["window"] = shown.window;
    r["level"] = shown.level;
    r["iso"] = v.settings.isoValue;
    if (v.settings.glyphs)
      r["glyphs"] = {{"method", config::toString(v.config.glyphMethod)},
                     {"convexity", config::toString(v.config.glyphConvexity)},
                     {"diameter_mm", v.config.glyphDiameterMm},
                     {"count", v.config.glyphCount},
                     {"seed", v.config.glyphSeed},
                     {"map_size", v.config.glyphMapSize},
                     {"map_diameter", v.config.glyphMapDiameter}};
    if (v.settings.functionalClasses > 0) r["functional_classes"] = v.settings.functionalClasses;
    if (v.settings.functionalHigh > v.settings.functionalLow)
      r["functional_window"] = {v.settings.functionalLow, v.settings.functionalHigh};
    if (shellMode) {
      r["shells"] = v.settings.shellCount;
      r["shells_disabled"] = v.config.shellsDisabled;
    }
    if ((v.settings.mode == render::RenderMode::Mip || shellMode) && v.settings.depthCue)
      r["depth_cue"] = {{"brightness", v.settings.cueBrightness},
                        {"amount", v.settings.cueAmount},
                        {"contrast", v.settings.cueContrast}};
    r["step_mm"] = v.settings.stepMm > 0 ? v.settings.stepMm : render::defaultStepMm(anatomy);
    r["sampling"] = config::toString(v.config.sampling);
    r["shading"] = v.settings.shading;
    r["jitter"] = v.settings.jitter;
    r["seed"] = v.settings.seed;
    r["annotated"] = v.config.annotate;
    if (v.settings.mode == render::RenderMode::Mpr) {
      r["plane_offset_mm"] = v.settings.planeOffsetMm;
      r["slab_mm"] = v.settings.slabMm;
    }
    r["functional_overlay"] = overlayShown;
    if (overlayShown) {
      r["overlay_opacity"] = v.settings.overlayOpacity;
      r["overlay_threshold"] = v.settings.overlayThreshold;
      r["functional_placement"] = placement ? placement->report["method"] : nlohmann::json("none");
    }
    r["ms_per_frame"] = frame.milliseconds;
    r["checksum_fnv1a64"] = fnv1a(frame.image.rgba);
    outputs.push_back({v.config.name + ".png", std::move(frame.image), r});
    std::cerr << "rendered " << v.config.name << " (" << toString(v.config.mode) << ", "
              << config::toString(v.config.view) << ") in " << static_cast<int>(frame.milliseconds)
              << " ms\n";
  }
  // All frames exist before anything is written: a failure leaves no partial output.
  fs::create_directories(o.outDir);
  nlohmann::json report;
  report["study"] = study.file.string();
  report["anatomical"] = anatomy.metadata().sourcePath;
  if (functional) {
    report["functional"] = functional->metadata().sourcePath;
    report["registration"] = placement->report;
  }
  report["value_range"] = {lo, hi};
  report["gl_backend"] = context->backend();
  report["gl_renderer"] = context->renderer();
  report["gl_version"] = context->version();
  report["mvw_version"] = kVersion;
  report["views"] = nlohmann::json::array();
  for (const auto& out : outputs) {
    io::writePng(out.image, fs::path(o.outDir) / out.file);
    report["views"].push_back(out.record);
  }
  io::writeTextAtomically(fs::path(o.outDir) / "render.json", report.dump(2) + "\n");
  std::cout << "wrote " << outputs.size() << " view(s) and render.json to " << o.outDir << "\n";
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render the views of a study config headless (EGL or OSMesa) to PNG + render.json");
  cmd->add_option("study", o->study, "Study config (.json)")->required();
  cmd->add_option("-o,--output", o->outDir, "Output folder")->required();
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
      ->check(CLI::PositiveNumber);
  cmd->add_option("--window", o->overrides.window, "Window width for projections")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--level", o->overrides.level, "Window centre for projections");
  cmd->add_option("--iso", o->overrides.iso, "Isosurface value");
  cmd->add_option("--sampling", o->overrides.sampling, "linear | nearest");
  cmd->add_option("--cue-brightness", o->overrides.cueBrightness,
                  "MIP depth cue: brightness beta0 (Heidrich 1995)");
  cmd->add_option("--cue-amount", o->overrides.cueAmount, "MIP depth cue: amount a (0 = none)");
  cmd->add_option("--cue-contrast", o->overrides.cueContrast,
                  "MIP depth cue: contrast b (1 = plain MIP)");
  cmd->add_flag("--perspective", o->overrides.perspective,
                "Perspective instead of orthographic projection");
  cmd->add_flag("--no-annotate", o->overrides.noAnnotate,
                "No orientation labels, scale bar or caption");
  addGlOption(*cmd, o->gl);
  cmd->callback([o] {
    if (o->overrides.window.has_value() != o->overrides.level.has_value())
      throw InputError(o->study, "--window and --level go together");
    runRender(*o);
  });
}

}  // namespace mvw::app
