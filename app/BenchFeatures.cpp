#include "BenchFeatures.h"

#include "HeadlessGl.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mvw/config/StudyConfig.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::app {

namespace {

struct FeatureBenchOptions {
  std::string study;
  std::optional<int> size;
  int frames = 12;
  std::string gl;
  pacs::Options pacs;  // the command line's --cache and time-outs (main.cpp)
};

// The cut face's anatomy (issue 36) counts as a feature: without it, the plain face.
bool hasFeature(const render::RenderSettings& s) {
  return s.glyphs || s.fusion || s.depthCue || render::showsAnatomyOnCutFace(s);
}

std::string featureName(const render::RenderSettings& s) {
  std::string name;
  if (s.glyphs) name += "glyphs";
  if (s.fusion) name += name.empty() ? "fusion" : "+fusion";
  if (s.depthCue) name += name.empty() ? "depth cue" : "+depth cue";
  if (render::showsAnatomyOnCutFace(s)) name += name.empty() ? "cut face" : "+cut face";
  return name;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void runFeatureBench(const FeatureBenchOptions& o) {
  mvw::study::ViewOverrides overrides;
  overrides.size = o.size;
  mvw::study::Session session(config::loadStudyConfig(o.study), overrides);
  auto context = output::makeHeadlessContext(o.gl);
  session.load(o.pacs);
  const config::StudyConfig& study = session.config();
  render::VolumeRenderer renderer(*context, session.anatomical());
  session.attach(renderer);
  std::printf(
      "mvw bench features: %s, %s %s, %d azimuth steps per view, with/without interleaved\n",
      study.file.filename().c_str(), context->backend().c_str(), context->renderer().c_str(),
      o.frames);
  std::printf("  %-30s %-11s %-15s %10s %10s %8s\n", "view", "mode", "feature", "without", "with",
              "ratio");
  for (const mvw::study::PlannedView& v : session.views(renderer)) {
    if (!hasFeature(v.settings)) continue;
    render::RenderSettings with = v.settings;
    render::RenderSettings without = with;
    without.glyphs = without.fusion = without.depthCue = false;
    without.cutFace = render::CutFace::Plain;
    renderer.render(with);  // compile both programs, upload the glyph map
    renderer.render(without);
    std::vector<double> ratios;
    double msWith = 0.0, msWithout = 0.0;
    for (int f = 0; f < o.frames; ++f) {
      with.camera.azimuthDeg = without.camera.azimuthDeg =
          v.settings.camera.azimuthDeg + 360.0 * f / o.frames;
      // Alternate which goes first, so neither always finds the caches warm.
      const bool withFirst = f % 2 == 0;
      const double a = renderer.render(withFirst ? with : without).milliseconds;
      const double b = renderer.render(withFirst ? without : with).milliseconds;
      const double w = withFirst ? a : b, wo = withFirst ? b : a;
      msWith += w;
      msWithout += wo;
      ratios.push_back(w / wo);
    }
    std::printf("  %-30s %-11s %-15s %7.1f ms %7.1f ms %7.3fx  (median of per-frame ratios %.3f)\n",
                v.config.name.c_str(), toString(v.config.mode).c_str(),
                featureName(v.settings).c_str(), msWithout / o.frames, msWith / o.frames,
                msWith / msWithout, median(ratios));
  }
}

}  // namespace

void addBenchFeaturesCommand(CLI::App& bench, const pacs::Options& pacs) {
  auto o = std::make_shared<FeatureBenchOptions>();
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
    runFeatureBench(*o);
  });
}

}  // namespace mvw::app
