#include "RenderRecord.h"

#include <cstdio>
#include <ostream>

#include "mvw/core/Version.h"
#include "mvw/render/Framing.h"
#include "mvw/study/Caption.h"

namespace mvw::output {

std::string fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

nlohmann::json viewRecord(const study::PlannedView& v, const study::Session& session,
                          const render::VolumeRenderer& renderer, const WindowLevel& shown,
                          bool overlayShown, const render::RenderedFrame& frame,
                          std::ostream& log) {
  const Volume& anatomy = session.anatomical();
  const double hi = renderer.valueRange().second;
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
  if (v.settings.gradientOpacity.on())
    r["gradient_opacity"] = {v.settings.gradientOpacity.low, v.settings.gradientOpacity.high};
  r["window"] = shown.window;
  r["level"] = shown.level;
  r["iso"] = v.settings.iso;
  // An isovalue no voxel reaches draws an empty image: legitimate to ask, but said.
  if (v.settings.mode == render::RenderMode::Isosurface && v.settings.iso > hi) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "iso %g lies above the volume's maximum %g: the isosurface is empty",
                  v.settings.iso, hi);
    r["notes"].push_back(text);
    log << "mvw render: note: view '" << v.config.name << "': " << text << "\n";
  }
  // Fusion asked of a mode that cannot show it: drawn without, and said (the caption and the
  // colour bar name no fusion either).
  if (v.settings.overlay.fusion && !takesFusion(v.settings.mode)) {
    const std::string text =
        v.settings.mode == render::RenderMode::Mpr
            ? "fusion is for composite, isosurface, mip, minip and average views: an mpr view "
              "shows the functional volume as its overlay (\"overlay\")"
            : toString(v.settings.mode) +
                  " cannot fuse the functional volume (its shells are the anatomy's alone): drawn "
                  "without; fusion is for composite, isosurface, mip, minip and average views";
    r["notes"].push_back(text);
    log << "mvw render: note: view '" << v.config.name << "': " << text << "\n";
  }
  if (v.settings.glyphs.on)
    r["glyphs"] = {
        {"method", config::toString(v.config.glyphs.method)},
        {"convexity", config::toString(v.config.glyphs.convexity)},
        {"diameter_mm", v.settings.glyphDiameterMm},
        {"spacing_mm", v.settings.glyphMap.placement == render::GlyphPlacement::BlueNoise
                           ? render::blueNoiseSpacing(v.settings.glyphMap.size) *
                                 v.settings.glyphDiameterMm / v.settings.glyphMap.diameter
                           : 0.0},
        {"count", v.config.glyphCount},
        {"seed", v.config.glyphSeed},
        {"map_size", v.config.glyphMapSize},
        {"map_diameter", v.config.glyphMapDiameter}};
  if (v.settings.glyphs.on && session.functional()) {
    // What the legend shows (issue 40): per entry its label, glyph kind, size and value.
    nlohmann::json entries = nlohmann::json::array();
    const render::GlyphLegend legend =
        study::glyphLegend(v, session.functional()->metadata().unit, renderer.functionalRange());
    for (const render::GlyphLegendEntry& e : legend.entries) {
      nlohmann::json entry = {{"label", e.label},
                              {"kind", e.size > 0 ? glyphKindName(e.kind) : "none"},
                              {"size", e.size}};
      if (e.value) entry["value"] = *e.value;
      entries.push_back(entry);
    }
    r["glyphs"]["legend"] = {{"title", legend.title}, {"entries", entries}};
    if (!v.settings.glyphs.classKinds.empty()) {
      nlohmann::json kinds = nlohmann::json::array();
      for (GlyphKind k : v.settings.glyphs.classKinds) kinds.push_back(glyphKindName(k));
      r["glyphs"]["class_kinds"] = kinds;
    }
  }
  if (v.settings.functionalClasses > 0) r["functional_classes"] = v.settings.functionalClasses;
  if (v.settings.functionalWindow.set())
    r["functional_window"] = {v.settings.functionalWindow.low, v.settings.functionalWindow.high};
  const bool shellMode = isShellMode(v.settings.mode);
  if (shellMode) {
    r["shells"] = v.settings.shells;
    r["shells_disabled"] = v.config.shellsDisabled;
  }
  if ((v.settings.mode == render::RenderMode::Mip || shellMode) && v.settings.depthCue.on)
    r["depth_cue"] = {{"brightness", v.settings.depthCue.brightness},
                      {"amount", v.settings.depthCue.amount},
                      {"contrast", v.settings.depthCue.contrast}};
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
  if (render::showsImageColors(v.settings)) r["colormap"] = toString(v.settings.imageColors->map);
  r["functional_overlay"] = overlayShown;
  if (session.segments() && v.settings.mode == render::RenderMode::Mpr)
    r["segment_outlines"] = session.segments()->names;
  if (overlayShown) {
    // As single precision, as the shader takes them (and as render.json has always said).
    r["overlay_opacity"] = static_cast<float>(v.settings.overlay.opacity);
    r["overlay_threshold"] = static_cast<float>(v.settings.overlay.threshold);
    r["overlay_colormap"] = toString(v.config.overlayColormap);
    r["functional_placement"] =
        session.placement() ? session.placement()->report["method"] : nlohmann::json("none");
  }
  r["ms_per_frame"] = frame.milliseconds;
  r["checksum_fnv1a64"] = fnv1a(frame.image.rgba);
  return r;
}

nlohmann::json studyRecord(const study::Session& session, const render::VolumeRenderer& renderer,
                           const render::GlContext& context) {
  nlohmann::json report;
  report["study"] = session.config().file.string();
  report["anatomical"] = session.anatomical().metadata().sourcePath;
  report["anatomical_notes"] = session.anatomical().metadata().notes;
  if (const Volume* functional = session.functional()) {
    report["functional"] = functional->metadata().sourcePath;
    report["functional_notes"] = functional->metadata().notes;
    report["registration"] = session.placement()->report;
  }
  const auto [lo, hi] = renderer.valueRange();
  report["value_range"] = {lo, hi};
  report["gl_backend"] = context.backend();
  report["gl_renderer"] = context.renderer();
  report["gl_version"] = context.version();
  report["gradient"] = render::toString(renderer.gradientSource());
  report["texture_runs"] = renderer.textureRuns();  // > 1: folded past the GL's 3D texture size
  report["mvw_version"] = kVersion;
  report["views"] = nlohmann::json::array();
  return report;
}

}  // namespace mvw::output
