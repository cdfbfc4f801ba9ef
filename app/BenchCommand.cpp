#include "BenchCommand.h"

#include "BenchRegister.h"
#include "CliChecks.h"
#include "HeadlessGl.h"

#include <memory>

#include <CLI/CLI.hpp>

#include "mvw/render/TransferFunction.h"
#include "mvw/validate/RenderBench.h"

namespace mvw::app {

namespace {

// `mvw bench features STUDY`: what each view's feature costs (validate::runFeatureBench).
void addBenchFeaturesCommand(CLI::App& bench, const pacs::Options& pacs) {
  auto o = std::make_shared<validate::FeatureBenchOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "features",
      "ms/frame of each view with its glyphs, fusion, depth cue or cut face and without, "
      "interleaved");
  cmd->add_option("study", o->study, "Study config (.json)")->required();
  cmd->add_option("--size", o->size, "Image width and height (default: each view's own)")
      ->check(CLI::Range(16, 4096));
  cmd->add_option("--frames", o->frames, "Azimuth steps per view")->check(CLI::Range(1, 3600));
  addGlOption(*cmd, o->gl);
  cmd->callback([o, &pacs] {
    o->pacs = pacs;
    validate::runFeatureBench(*o);
  });
}

}  // namespace

void addBenchCommand(CLI::App& app, const pacs::Options& pacs) {
  auto o = std::make_shared<validate::RenderBenchOptions>();
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
    validate::runRenderBench(*o);
  });
  addBenchRegisterCommand(*bench);
  addBenchFeaturesCommand(*bench, pacs);
}

}  // namespace mvw::app
