#pragma once
// `mvw bench render` and `mvw bench features`: benchmarks (not tests) of the renderer, printed
// on stdout. app/ parses their options and calls these (as RegistrationBench for `mvw bench
// register`).
#include <optional>
#include <string>
#include <vector>

#include "mvw/pacs/Pacs.h"
#include "mvw/render/RenderSettings.h"

namespace mvw::validate {

struct RenderBenchOptions {
  std::string study;
  int size = 512;
  int frames = 36;
  std::string modes = "mip,composite,isosurface";
  std::string preset = "ct-bone";
  double stepMm = 0.0;
  bool noShading = false;
  std::string gl;
  std::string gradient = "auto";
  pacs::Options pacs;  // the command line's --cache and time-outs
};

// ms/frame of each render mode over an azimuth orbit, and each mode's first frame's PSNR
// against a 4x oversampled reference.
void runRenderBench(const RenderBenchOptions& o);

struct FeatureBenchOptions {
  std::string study;
  std::optional<int> size;
  int frames = 12;
  std::string gl;
  pacs::Options pacs;  // the command line's --cache and time-outs
};

// What each view's feature (glyphs, colour fusion, depth cue, cut face) costs over the same
// view without it, rendered interleaved over an azimuth orbit (see tests/bench/feature-cost).
void runFeatureBench(const FeatureBenchOptions& o);

// Whether a view has a feature the feature bench measures. The cut face's anatomy (issue 36)
// counts as one: without it, the plain face.
bool hasBenchFeature(const render::RenderSettings& s);

// "glyphs+fusion+depth cue+cut face": the features of a view, in that order.
std::string benchFeatureName(const render::RenderSettings& s);

// The view without its features: no glyphs, fusion or depth cue, a plain cut face.
render::RenderSettings withoutBenchFeatures(render::RenderSettings s);

// The median (the mean of the middle two of an even count); v not empty.
double median(std::vector<double> v);

}  // namespace mvw::validate
