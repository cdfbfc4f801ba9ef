#include "mvw/validate/RenderBench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/output/HeadlessGl.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Session.h"
#include "mvw/study/StudyLoader.h"
#include "mvw/study/ViewPlan.h"
#include "mvw/validate/ImageMetrics.h"

namespace mvw::validate {

void runRenderBench(const RenderBenchOptions& o) {
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
  // The ceiling, at 256 samples a pixel (the order of a ray's through a head CT at its step),
  // measured again before each mode, whose fraction of it takes that measurement: the load
  // on a shared machine moves both alike.
  const int ceilingSamples = 256;
  auto measureCeiling = [&] { return renderer.sampleCeiling({o.size, o.size}, ceilingSamples); };
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::printf(
      "  ceiling: %.0f M trilinear samples/s (one fetch of the intensity texture and an add "
      "per sample, %d per pixel, fastest of 3 draws); %u cores, LP_NUM_THREADS %s\n",
      measureCeiling() * 1e-6, ceilingSamples, std::thread::hardware_concurrency(),
      threads ? threads : "unset (llvmpipe: one thread per core)");
  for (render::RenderMode mode : modes) {
    render::RenderSettings s;
    s.mode = mode;
    s.size = {o.size, o.size};
    s.transfer = render::transferPreset(o.preset);
    s.camera.view = render::StandardView::Anterior;
    s.stepMm = o.stepMm;
    s.shading = !o.noShading;
    renderer.render(s);  // compiles the program
    const double ceiling = measureCeiling();
    double total = 0.0, samples = 0.0;
    for (int f = 0; f < o.frames; ++f) {
      s.camera.azimuthDeg = 360.0 * f / o.frames;
      total += renderer.render(s).milliseconds;
      samples += renderer.nominalSamples(s);
    }
    const double ms = total / o.frames;
    // Every sample the rays would take without skipping, per second: skipping can lift a
    // mode past the ceiling.
    const double perSecond = samples / (total * 1e-3);
    // Quality: the first frame against a 4x oversampled reference (a quarter of the step).
    s.camera.azimuthDeg = 0.0;
    const Image image = renderer.render(s).image;
    const double step = s.stepMm > 0 ? s.stepMm : render::defaultStepMm(volume);
    s.stepMm = step / 4.0;
    const Image reference = renderer.render(s).image;
    std::printf(
        "  %-11s %8.1f ms/frame  %6.2f fps  step %.3f mm  PSNR %.1f dB vs 4x oversampled"
        "  %.0f M samples/s = %.2f of the ceiling (%.0f M/s)\n",
        render::toString(mode).c_str(), ms, 1000.0 / ms, step, psnr(image, reference),
        perSecond * 1e-6, perSecond / ceiling, ceiling * 1e-6);
  }
}

bool hasBenchFeature(const render::RenderSettings& s) {
  return s.glyphs.on || s.overlay.fusion || s.depthCue.on || render::showsAnatomyOnCutFace(s);
}

std::string benchFeatureName(const render::RenderSettings& s) {
  std::string name;
  if (s.glyphs.on) name += "glyphs";
  if (s.overlay.fusion) name += name.empty() ? "fusion" : "+fusion";
  if (s.depthCue.on) name += name.empty() ? "depth cue" : "+depth cue";
  if (render::showsAnatomyOnCutFace(s)) name += name.empty() ? "cut face" : "+cut face";
  return name;
}

render::RenderSettings withoutBenchFeatures(render::RenderSettings s) {
  s.glyphs.on = s.overlay.fusion = s.depthCue.on = false;
  s.cutFace = render::CutFace::Plain;
  return s;
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
  // One row: `with` against `without`, interleaved over the orbit.
  auto row = [&](const std::string& view, const render::RenderSettings& with0,
                 const render::RenderSettings& without0, const std::string& feature) {
    render::RenderSettings with = with0, without = without0;
    renderer.render(with);  // compile both programs, upload the glyph map
    renderer.render(without);
    std::vector<double> ratios;
    double msWith = 0.0, msWithout = 0.0;
    for (int f = 0; f < o.frames; ++f) {
      with.camera.azimuthDeg = without.camera.azimuthDeg =
          with0.camera.azimuthDeg + 360.0 * f / o.frames;
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
                view.c_str(), toString(with0.mode).c_str(), feature.c_str(), msWithout / o.frames,
                msWith / o.frames, msWith / msWithout, median(ratios));
  };
  for (const mvw::study::PlannedView& v : session.views(renderer)) {
    if (!hasBenchFeature(v.settings)) continue;
    row(v.config.name, v.settings, withoutBenchFeatures(v.settings), benchFeatureName(v.settings));
    // Fusion with another feature: also fusion alone, against the same view unfused (a fused
    // depth-cued MIP against the plain depth-cued one).
    render::RenderSettings unfused = v.settings;
    unfused.overlay.fusion = false;
    if (v.settings.overlay.fusion && hasBenchFeature(unfused))
      row(v.config.name, v.settings, unfused, "fusion alone");
  }
}

}  // namespace mvw::validate
