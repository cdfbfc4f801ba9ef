#include "BenchCommand.h"

#include "BenchFeatures.h"
#include "BenchRegister.h"
#include "CliChecks.h"
#include "HeadlessGl.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/validate/ImageMetrics.h"

namespace mvw::app {

namespace {

struct BenchOptions {
  std::string study;
  int size = 512;
  int frames = 36;
  std::string modes = "mip,composite,isosurface";
  std::string preset = "ct-bone";
  double stepMm = 0.0;
  bool noShading = false;
  std::string gl;
  std::string gradient = "auto";
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

void runBench(const BenchOptions& o) {
  std::vector<render::RenderMode> modes;
  std::stringstream list(o.modes);
  for (std::string name; std::getline(list, name, ',');) {
    const auto m = render::parseRenderMode(name);
    if (!m) throw InputError(o.study, "unknown mode '" + name + "' in --modes");
    modes.push_back(*m);
  }
  const auto study = config::loadStudyConfig(o.study);
  auto context = output::makeHeadlessContext(o.gl);
  const Volume volume = mvw::study::readSource(study.anatomical, {}, o.pacs);
  const auto t0 = std::chrono::steady_clock::now();
  render::VolumeRenderer renderer(*context, volume, render::parseGradientSource(o.gradient));
  const double uploadMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const glm::ivec3 d = volume.dimensions();
  std::printf("mvw bench render: %s, %s, %s, %d x %d x %d, %d x %d pixels, %d frames per mode\n",
              context->backend().c_str(), context->renderer().c_str(), context->version().c_str(),
              d.x, d.y, d.z, o.size, o.size, o.frames);
  std::printf("  upload (volume, gradient, blocks): %.0f ms, gradient from the %s%s\n", uploadMs,
              render::toString(renderer.gradientSource()),
              renderer.textureRuns() > 1
                  ? (", slices folded into " + std::to_string(renderer.textureRuns()) +
                     " runs (more than the GL's largest 3D texture)")
                        .c_str()
                  : "");
  for (render::RenderMode mode : modes) {
    render::RenderSettings s;
    s.mode = mode;
    s.size = {o.size, o.size};
    s.transfer = render::transferPreset(o.preset);
    s.camera.view = render::StandardView::Anterior;
    s.stepMm = o.stepMm;
    s.shading = !o.noShading;
    renderer.render(s);  // compiles the program
    double total = 0.0;
    for (int f = 0; f < o.frames; ++f) {
      s.camera.azimuthDeg = 360.0 * f / o.frames;
      total += renderer.render(s).milliseconds;
    }
    const double ms = total / o.frames;
    // Quality: the first frame against a 4x oversampled reference (a quarter of the step).
    s.camera.azimuthDeg = 0.0;
    const Image image = renderer.render(s).image;
    const double step = s.stepMm > 0 ? s.stepMm : render::defaultStepMm(volume);
    s.stepMm = step / 4.0;
    const Image reference = renderer.render(s).image;
    std::printf("  %-11s %8.1f ms/frame  %6.2f fps  step %.3f mm  PSNR %.1f dB vs 4x oversampled\n",
                render::toString(mode).c_str(), ms, 1000.0 / ms, step,
                validate::psnr(image, reference));
  }
}

}  // namespace

void addBenchCommand(CLI::App& app, const pacs::Options& pacs) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks (not tests): print timings");
  CLI::App* cmd =
      bench->add_subcommand("render", "ms/frame of each render mode over an azimuth orbit");
  bench->require_subcommand(1);
  cmd->add_option("study", o->study, "Study config (.json)")->required();
  cmd->add_option("--size", o->size, "Image width and height")->check(CLI::Range(16, 4096));
  cmd->add_option("--frames", o->frames, "Azimuth steps per mode")->check(CLI::Range(1, 3600));
  cmd->add_option("--modes", o->modes, "Comma-separated modes")->check(nonEmpty());
  cmd->add_option("--preset", o->preset, "Transfer function for composite")
      ->check(CLI::IsMember(render::transferPresetNames()));
  cmd->add_option("--step", o->stepMm, "Sample distance in mm (default: half the smallest spacing)")
      ->check(CLI::Range(1e-3, 1e3));
  cmd->add_flag("--no-shading", o->noShading, "Composite without Phong shading");
  addGlOption(*cmd, o->gl);
  addGradientOption(*cmd, o->gradient);
  cmd->callback([o, &pacs] {
    o->pacs = pacs;
    runBench(*o);
  });
  addBenchRegisterCommand(*bench);
  addBenchFeaturesCommand(*bench, pacs);
}

}  // namespace mvw::app
