#include "mvw/study/ViewPlan.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>

#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/io/ColorPalettes.h"
#include "mvw/io/LabelTable.h"
#include "mvw/render/Framing.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/study/ModalityDefaults.h"

namespace mvw::study {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

render::StandardView standardView(config::ViewName view) {
  using config::ViewName;
  using render::StandardView;
  switch (view) {
    case ViewName::Anterior:
      return StandardView::Anterior;
    case ViewName::Posterior:
      return StandardView::Posterior;
    case ViewName::Left:
      return StandardView::Left;
    case ViewName::Right:
      return StandardView::Right;
    case ViewName::Superior:
      return StandardView::Superior;
    case ViewName::Inferior:
      return StandardView::Inferior;
    // The MPR planes as radiology displays them: axial seen from the feet, coronal from the
    // front, sagittal from the patient's left.
    case ViewName::Axial:
      return StandardView::Inferior;
    case ViewName::Coronal:
      return StandardView::Anterior;
    case ViewName::Sagittal:
      return StandardView::Left;
  }
  return StandardView::Anterior;
}

config::ViewName viewName(render::StandardView view) {
  using config::ViewName;
  using render::StandardView;
  switch (view) {
    case StandardView::Anterior:
      return ViewName::Anterior;
    case StandardView::Posterior:
      return ViewName::Posterior;
    case StandardView::Left:
      return ViewName::Left;
    case StandardView::Right:
      return ViewName::Right;
    case StandardView::Superior:
      return ViewName::Superior;
    case StandardView::Inferior:
      return ViewName::Inferior;
  }
  return ViewName::Anterior;
}

namespace {

namespace fs = std::filesystem;

// The blue-noise map of a view: its spacing (autoSpacingMm unless the config gives one; at
// least what a diameter alone asks for) and diameter (a fraction of the spacing unless given).
void setBlueNoiseMap(render::RenderSettings& s, const config::ViewConfig& v, double autoSpacingMm) {
  const double spacing = v.glyphSpacingMm.value_or(
      std::max(autoSpacingMm, v.glyphDiameterMm.value_or(0.0) / kBlueNoiseDiameterFraction));
  s.glyphDiameterMm = v.glyphDiameterMm.value_or(kBlueNoiseDiameterFraction * spacing);
  s.glyphMap = render::blueNoiseGlyphMap(spacing, s.glyphDiameterMm, v.glyphSeed);
}

// The labels a view chose for glyphs, by number or by name in the atlas's label table (beside
// the functional volume: io::labelTableBeside). "none" drops a label.
std::vector<render::LabelGlyph> chosenLabels(const config::StudyConfig& study,
                                             const config::ViewConfig& v) {
  const std::string where = "view '" + v.name + "': glyphs.labels: ";
  if (study.functionalKind != config::FunctionalKind::Labels)
    throw InputError(study.file, where + "the functional volume must be a label map (kind labels)");
  std::map<int, std::string> names;
  std::optional<fs::path> table;
  if (study.functional) table = io::labelTableBeside(study.functional->path);
  if (table) names = io::readLabelTable(*table);
  std::vector<render::LabelGlyph> out;
  for (const config::LabelChoice& c : v.glyphLabels) {
    render::LabelGlyph g;
    const bool numeric = !c.label.empty() && c.label.size() < 10 &&
                         std::all_of(c.label.begin(), c.label.end(), ::isdigit);
    if (numeric) {
      g.label = std::stoi(c.label);
      if (g.label < 1 || g.label > kMaxGlyphLabel)
        throw InputError(study.file, where + "label " + c.label + " is outside 1 .. " +
                                         std::to_string(kMaxGlyphLabel));
      if (auto it = names.find(g.label); it != names.end()) g.name = it->second;
    } else {
      if (!table)
        throw InputError(study.file, where + "'" + c.label +
                                         "' is a name, but no label table lies beside " +
                                         study.functional->path.string() +
                                         " (X.nii.txt or X.txt): give label numbers");
      const auto it = std::find_if(names.begin(), names.end(),
                                   [&](const auto& n) { return n.second == c.label; });
      if (it == names.end())
        throw InputError(study.file,
                         where + "no label named '" + c.label + "' in " + table->string());
      // A name the table gives to two labels cannot choose one.
      const auto twin = std::find_if(std::next(it), names.end(),
                                     [&](const auto& n) { return n.second == c.label; });
      if (twin != names.end())
        throw InputError(study.file, where + "'" + c.label + "' names labels " +
                                         std::to_string(it->first) + " and " +
                                         std::to_string(twin->first) + " in " + table->string() +
                                         ": give the label number");
      g.label = it->first, g.name = it->second;
    }
    if (g.label > kMaxGlyphLabel)
      throw InputError(study.file, where + "label " + std::to_string(g.label) + " is above " +
                                       std::to_string(kMaxGlyphLabel));
    if (c.kind == config::LabelGlyphKind::None) continue;
    g.kind = *config::glyphKindOf(c.kind);
    out.push_back(std::move(g));
  }
  return out;
}

}  // namespace

double defaultGlyphSpacingMm(double functionalVoxelMm, double mmPerPixel, double minSize,
                             bool kinds) {
  // The weakest bump (minSize glyph radii, the glyph kBlueNoiseDiameterFraction of the
  // spacing) must be kGlyphMinBumpPixels in radius on the image; with kinds, a full-size
  // glyph kGlyphKindRadiusPixels.
  const double radiusPerSpacing = 0.5 * kBlueNoiseDiameterFraction * std::max(minSize, 0.2);
  double visible = kGlyphMinBumpPixels * mmPerPixel / radiusPerSpacing;
  if (kinds)
    visible =
        std::max(visible, kGlyphKindRadiusPixels * mmPerPixel / (0.5 * kBlueNoiseDiameterFraction));
  return std::min(std::max(functionalVoxelMm, visible), std::max(kGlyphSpacingMm, visible));
}

void applyGlyphScale(PlannedView& view, const Volume& anatomy, const Volume& functional) {
  const config::ViewConfig& v = view.config;
  if (v.glyphPlacement != config::GlyphPlacement::BlueNoise || v.glyphSpacingMm) return;
  render::RenderSettings& s = view.settings;
  const double pixels = std::max(1, std::min(s.size.x, s.size.y));
  const double mmPerPixel =
      2.0 * render::framingSphere(anatomy).radius / std::max(s.camera.zoom, 1e-3) / pixels;
  const glm::dvec3 fv = functional.spacing();
  const double voxel = std::max({fv.x, fv.y, fv.z});
  setBlueNoiseMap(
      s, v, defaultGlyphSpacingMm(voxel, mmPerPixel, v.glyphs.minSize, render::usesGlyphKinds(s)));
}

ColorTable colorTable(ColorMap map) {
  return map == ColorMap::HotMetal ? render::hotMetalTable() : io::standardColorTable(map);
}

void applyColorMaps(render::RenderSettings& s, ColorMap image, ColorMap overlay) {
  s.imageColors.reset();
  s.overlayColors.reset();
  if (image != ColorMap::Grey) s.imageColors = colorTable(image);
  if (overlay != ColorMap::HotMetal) s.overlayColors = colorTable(overlay);
}

namespace {

// The command line's colour maps and orbit mode, parsed once for every view.
struct ParsedOverrides {
  std::optional<ColorMap> colormap, overlayColormap;
  std::optional<config::OrbitMode> orbitMode;
};

ParsedOverrides parseOverrides(const config::StudyConfig& study, const ViewOverrides& o) {
  auto colorMapOption = [&](const std::optional<std::string>& name, const char* option) {
    std::optional<ColorMap> map;
    if (name) {
      map = parseColorMap(*name);
      if (!map)
        throw InputError(study.file, std::string(option) + " '" + *name +
                                         "' is not a colour map (" + joined(colorMapNames()) + ")");
    }
    return map;
  };
  ParsedOverrides p;
  p.colormap = colorMapOption(o.colormap, "--colormap");
  p.overlayColormap = colorMapOption(o.overlayColormap, "--overlay-colormap");
  if (o.orbitMode) {
    p.orbitMode = config::parseOrbitMode(*o.orbitMode);
    if (!p.orbitMode) throw InputError(study.file, "--orbit-mode must be spin or rock");
  }
  if (o.orbit && (*o.orbit < 2 || *o.orbit > config::kMaxOrbitFrames))
    throw InputError(study.file, "--orbit must be 2.." + std::to_string(config::kMaxOrbitFrames) +
                                     " frames, not " + std::to_string(*o.orbit));
  return p;
}

// The command line's numbers within the config's own ranges (NaN is in none).
void checkOverrideNumbers(const ViewOverrides& o, const fs::path& file) {
  auto ranged = [&](const std::optional<double>& x, const char* flag, const char* key) {
    const auto [lo, hi] = config::viewNumberRange(key);
    if (!x || (*x >= lo && *x <= hi)) return;
    char text[160];
    std::snprintf(text, sizeof text, "%s %g is outside %g .. %g", flag, *x, lo, hi);
    throw InputError(file, text);
  };
  ranged(o.azimuth, "--azimuth", "azimuth");
  ranged(o.elevation, "--elevation", "elevation");
  ranged(o.roll, "--roll", "roll");
  ranged(o.zoom, "--zoom", "zoom");
  ranged(o.window, "--window", "window");
  ranged(o.level, "--level", "level");
  ranged(o.iso, "--iso", "iso");
  ranged(o.cueBrightness, "--cue-brightness", "depth_cue.brightness");
  ranged(o.cueAmount, "--cue-amount", "depth_cue.amount");
  ranged(o.cueContrast, "--cue-contrast", "depth_cue.contrast");
}

// A view's config with the command line's overrides applied, each checked as the config
// checks its key.
void applyOverrides(config::ViewConfig& v, const ViewOverrides& o, const ParsedOverrides& parsed,
                    const fs::path& file) {
  if (o.mode) {
    const auto mode = parseRenderMode(*o.mode);
    if (!mode)
      throw InputError(
          file, "--mode '" + *o.mode + "' is not a mode (" + joined(renderModeNames()) + ")");
    v.mode = *mode;
  }
  if (o.view) {
    const auto view = config::parseViewName(*o.view);
    if (!view)
      throw InputError(file,
                       "--view '" + *o.view + "' is not a view (" + config::viewNameList() + ")");
    v.view = *view;
  }
  if (o.preset) v.preset = *o.preset;
  if (o.sampling) {
    const auto sampling = config::parseSampling(*o.sampling);
    if (!sampling) throw InputError(file, "--sampling must be linear or nearest");
    v.sampling = *sampling;
  }
  checkOverrideNumbers(o, file);
  // The config's zoom keeps its field in the square image (issue 36 item 4).
  if (o.size && v.fitAspect <= 0.0) v.fitAspect = double(v.width) / v.height;
  if (o.size) v.width = v.height = *o.size;
  if (o.azimuth) v.azimuth = *o.azimuth;
  if (o.elevation) v.elevation = *o.elevation;
  if (o.roll) v.roll = *o.roll;
  if (o.zoom) v.zoom = *o.zoom;
  if (o.window) v.window.window = *o.window;
  if (o.level) v.window.level = *o.level;
  if (o.iso) v.iso = *o.iso;
  if (o.noAnnotate) v.annotate = false;
  if (o.cueBrightness || o.cueAmount || o.cueContrast) v.depthCue.on = true;
  if (o.cueBrightness) v.depthCue.brightness = *o.cueBrightness;
  if (o.cueAmount) v.depthCue.amount = *o.cueAmount;
  if (o.cueContrast) v.depthCue.contrast = *o.cueContrast;
  if (o.perspective) v.perspective = true;
  // A mode overridden to one without an image colour map drops the view's.
  if (!takesImageColors(v.mode)) v.colormap = ColorMap::Grey;
  if (parsed.colormap && takesImageColors(v.mode)) v.colormap = *parsed.colormap;
  // And one whose fused projection is always the maximum drops the view's functional mean.
  if (o.mode && !takesFusionMean(v.mode)) v.overlay.projection = FusionProjection::Max;
  if (parsed.overlayColormap) v.overlayColormap = *parsed.overlayColormap;
  // --orbit turns the views that can turn about the long axis (not those looking along it).
  const render::StandardView sight = standardView(v.view);
  const bool alongS =
      sight == render::StandardView::Superior || sight == render::StandardView::Inferior;
  if (o.orbit && !alongS) v.orbit.frames = *o.orbit;
  if (parsed.orbitMode) v.orbit.mode = *parsed.orbitMode;
}

// The view's size, transfer function, camera, sampling and crop.
void setViewGeometry(render::RenderSettings& s, const config::ViewConfig& v, const fs::path& file) {
  if (v.width < 1 || v.width > 8192 || v.height < 1 || v.height > 8192)
    throw InputError(file, "view '" + v.name + "': size must be 1..8192");
  if (!v.preset.empty()) {
    try {
      s.transfer = render::transferPreset(v.preset);
    } catch (const Error& e) {
      throw InputError(file, "view '" + v.name + "': " + e.what());
    }
  }
  s.gradientOpacity = v.gradientOpacity;
  s.mode = v.mode;
  s.size = {v.width, v.height};
  s.camera.view = standardView(v.view);
  s.camera.azimuthDeg = v.azimuth;
  s.camera.elevationDeg = v.elevation;
  s.camera.rollDeg = v.roll;
  s.camera.zoom = v.zoom;
  s.camera.fitAspect = v.fitAspect > 0.0 ? v.fitAspect : double(v.width) / v.height;
  s.camera.panMm = {v.pan[0], v.pan[1]};
  s.camera.perspective = v.perspective;
  s.window = v.window;
  s.iso = v.iso;
  s.stepMm = v.stepMm;
  s.shading = v.shading;
  s.linear = v.sampling == config::Sampling::Linear;
  s.jitter = v.jitter;
  s.seed = v.seed;
  s.background = {v.background[0], v.background[1], v.background[2]};
  s.crop = v.crop;
  s.cutFace = v.cutFace;
}

// The glyphs: their style and their map (the config's placement, spacing and diameter made the
// renderer's map; describeView turns it back), checked against the study and the mode.
void setGlyphs(render::RenderSettings& s, const config::ViewConfig& v,
               const config::StudyConfig& study) {
  s.glyphs = v.glyphs;
  s.glyphMap = {v.glyphMapSize, v.glyphCount, v.glyphMapDiameter, v.glyphSeed};
  {
    // The map follows the config's placement even while glyphs are off, so a viewer that
    // switches them on shows the same glyphs `mvw render` would. A map that cannot hold the
    // request is bad input, said before any GL work.
    const bool paper = v.glyphPlacement == config::GlyphPlacement::Paper;
    const std::string keys = paper ? "glyphs.count / glyphs.map_diameter / glyphs.map_size"
                                   : "glyphs.diameter_mm / glyphs.spacing_mm";
    try {
      if (paper)
        s.glyphDiameterMm = v.glyphDiameterMm.value_or(kPaperGlyphDiameterMm);
      else  // an automatic spacing is provisional until applyGlyphScale knows the volumes
        setBlueNoiseMap(s, v, kGlyphSpacingMm);
      if (v.glyphs.on) render::makeGlyphMap(s.glyphMap, /*texels=*/false);
    } catch (const InputError&) {
      throw;
    } catch (const Error& e) {
      throw InputError(study.file, "view '" + v.name + "': " + keys + ": " + e.what());
    }
  }
  if (v.glyphs.on && !study.functional)
    throw InputError(study.file,
                     "view '" + v.name + "': glyphs need a functional volume in the study");
  if (v.glyphs.on &&
      (s.mode != render::RenderMode::Composite && s.mode != render::RenderMode::Isosurface))
    throw InputError(study.file,
                     "view '" + v.name + "': glyphs work in composite and isosurface modes");
}

// The functional volume's window, the shells and the depth cue, the planes, overlay, fusion and
// glyph labels.
void setFunctional(render::RenderSettings& s, const config::ViewConfig& v,
                   const config::StudyConfig& study) {
  s.functionalWindow = v.functionalWindow;
  s.lightOffset = {v.light[0], v.light[1]};
  s.shells = v.shells;
  if (!v.shellsDisabled.empty()) {
    s.shellEnabled.assign(static_cast<std::size_t>(v.shells), true);
    for (int k : v.shellsDisabled) s.shellEnabled[static_cast<std::size_t>(k - 1)] = false;
  }
  s.depthCue = v.depthCue;
  s.planeOffsetMm = v.planeOffsetMm;
  s.slabMm = v.slabMm;
  s.overlay = v.overlay;
  s.segmentationOutlines = v.segmentationOutlines;
  s.functionalClasses = v.functionalClasses;
  if (!v.glyphLabels.empty()) s.glyphLabels = chosenLabels(study, v);
  if (v.overlay.fusion && !study.functional)
    throw InputError(study.file,
                     "view '" + v.name + "': fusion needs a functional volume in the study");
  if (v.overlay.projection == FusionProjection::Mean && !takesFusionMean(s.mode))
    throw InputError(study.file, "view '" + v.name +
                                     "': fusion_projection mean is for minip and average views "
                                     "(a fused mip shows the functional maximum)");
}

// One view of the study, its overrides applied: its render settings, checked.
PlannedView planView(const config::StudyConfig& study, const config::ViewConfig& v) {
  PlannedView p;
  auto& s = p.settings;
  setViewGeometry(s, v, study.file);
  setGlyphs(s, v, study);
  setFunctional(s, v, study);
  const render::StandardView along = standardView(v.view);
  if (v.orbit.on() &&
      (along == render::StandardView::Superior || along == render::StandardView::Inferior))
    throw InputError(study.file, "view '" + v.name +
                                     "': an orbit turns about the patient's long axis, which " +
                                     config::toString(v.view) + " looks along");
  applyColorMaps(s, v.colormap, v.overlayColormap);
  p.presetName = v.preset;
  p.config = v;
  return p;
}

}  // namespace

std::vector<PlannedView> planViews(const config::StudyConfig& study, const ViewOverrides& o) {
  const ParsedOverrides parsed = parseOverrides(study, o);
  std::vector<PlannedView> out;
  for (config::ViewConfig v : study.render.views) {
    applyOverrides(v, o, parsed, study.file);
    out.push_back(planView(study, v));
  }
  // Overrides that reach no view are mistakes, said as such.
  if (parsed.colormap && std::none_of(out.begin(), out.end(), [](const PlannedView& p) {
        return takesImageColors(p.config.mode);
      }))
    throw InputError(study.file,
                     "--colormap colours mip, minip, average and mpr views, and the study has "
                     "none (--overlay-colormap colours the functional overlay)");
  if (o.orbit && std::none_of(out.begin(), out.end(),
                              [](const PlannedView& p) { return p.config.orbit.on(); }))
    throw InputError(study.file,
                     "--orbit turns views about the patient's long axis, and every view of the "
                     "study looks along it (superior, inferior or axial)");
  return out;
}

void checkViewsAgainstAnatomy(const std::vector<PlannedView>& views, const Volume& anatomy,
                              const std::filesystem::path& file) {
  const glm::dvec3 spacing = anatomy.spacing();
  const double finest = std::min({spacing.x, spacing.y, spacing.z}) / 100.0;
  const auto [lo, hi] = render::worldBounds(anatomy);
  // The renderer places an MPR plane this far at most from the framing sphere's centre.
  const double radius = render::framingSphere(anatomy).radius;
  for (const PlannedView& v : views) {
    const render::RenderSettings& s = v.settings;
    const std::string view = "view '" + v.config.name + "': ";
    if (s.stepMm > 0.0 && s.stepMm < finest)
      throw InputError(file, view + "step_mm " + shortNumber(s.stepMm) +
                                 " is below 1/100 of the smallest voxel spacing (" +
                                 shortNumber(100.0 * finest) +
                                 " mm): no ray can take so many samples (0: half the spacing)");
    if (s.crop.minMm && s.crop.maxMm)
      for (int a = 0; a < 3; ++a)
        if ((*s.crop.maxMm)[a] < lo[a] || (*s.crop.minMm)[a] > hi[a])
          throw InputError(file, view + "crop_mm misses the volume along " + "LPS"[a] + " (" +
                                     shortNumber((*s.crop.minMm)[a]) + " .. " +
                                     shortNumber((*s.crop.maxMm)[a]) + " mm; the volume spans " +
                                     shortNumber(lo[a]) + " .. " + shortNumber(hi[a]) + " mm)");
    if (s.mode == render::RenderMode::Mpr && std::abs(s.planeOffsetMm) > radius)
      throw InputError(file, view + "plane_offset_mm " + shortNumber(s.planeOffsetMm) +
                                 " puts the plane outside the volume (at most " +
                                 shortNumber(radius) + " mm either side of its centre)");
  }
}

void applyDefaultPreset(PlannedView& view, const Volume& anatomy) {
  if (!view.presetName.empty()) return;
  view.presetName = defaultPreset(anatomy);
  view.settings.transfer = render::transferPreset(view.presetName);
}

void applyAttributeDefaults(PlannedView& view, config::FunctionalKind kind,
                            const Volume& functional, std::pair<double, double> range) {
  // Glyph views only: there the window's low end is the threshold below which no glyph shows.
  // A colour overlay or fusion keeps the full range as its colour scale (its threshold is a
  // fraction of the window: a raised low end would hide moderate uptake twice over).
  if (!view.settings.glyphs.on) return;
  if (view.config.functionalWindow.set() || view.config.functionalClasses > 0) return;
  const ValueWindow window = defaultAttributeWindow(kind, functional, range);
  if (window.set()) view.settings.functionalWindow = window;
}

void applyModalityView(PlannedView& view, const Volume& anatomy, const ModalityDefaults& defaults) {
  if (!isEmission(anatomy)) return;
  render::RenderSettings& s = view.settings;
  if (view.config.implied) {
    s.mode = defaults.mode3d;
    view.config.mode = defaults.mode3d;
    // A colour map from the command line (--colormap) stays.
    if (view.config.colormap == ColorMap::Grey) view.config.colormap = defaults.mipColors;
    applyColorMaps(s, view.config.colormap, view.config.overlayColormap);
  }
  if (view.config.window.set() ||
      (s.mode != render::RenderMode::Mip && s.mode != render::RenderMode::Mpr))
    return;
  s.window = defaults.mpr;
}

void applyCutFaceWindow(PlannedView& view, const WindowLevel& mpr) {
  if (view.config.window.set() || !render::showsAnatomyOnCutFace(view.settings)) return;
  view.settings.window = mpr;
}

config::ViewConfig describeView(const render::RenderSettings& s, const std::string& name,
                                const std::string& preset) {
  config::ViewConfig v;
  v.name = name;
  v.mode = s.mode;
  v.view = viewName(s.camera.view);
  v.azimuth = s.camera.azimuthDeg;
  v.elevation = s.camera.elevationDeg;
  v.roll = s.camera.rollDeg;
  v.zoom = render::fittedZoom(s.camera, s.size);  // the zoom at the described size's shape
  v.pan = {s.camera.panMm.x, s.camera.panMm.y};
  v.perspective = s.camera.perspective;
  v.width = s.size.x;
  v.height = s.size.y;
  v.preset = preset;
  if (s.window.set()) v.window = s.window;
  v.iso = s.iso;
  v.stepMm = s.stepMm;
  v.shading = s.shading;
  v.sampling = s.linear ? config::Sampling::Linear : config::Sampling::Nearest;
  v.jitter = s.jitter;
  v.seed = s.seed;
  v.background = {s.background.r, s.background.g, s.background.b};
  v.cutFace = s.cutFace;
  v.crop = s.crop;
  // Glyphs only where they show (a viewer may leave them on while it shows a MIP): a saved MIP
  // with glyphs would not load.
  v.glyphs = s.glyphs;
  v.glyphs.on =
      s.glyphs.on && (s.mode == RenderMode::Composite || s.mode == RenderMode::Isosurface);
  v.glyphDiameterMm = s.glyphDiameterMm;  // what is shown, explicit
  v.glyphMapSize = s.glyphMap.size;
  v.glyphCount = s.glyphMap.count;
  v.glyphMapDiameter = s.glyphMap.diameter;
  v.glyphSeed = s.glyphMap.seed;
  // Chosen labels by number (a table beside the volume names them again), in the modes
  // that draw glyphs, kept while glyphs are switched off.
  if (s.mode == RenderMode::Composite || s.mode == RenderMode::Isosurface)
    for (const render::LabelGlyph& l : s.glyphLabels)
      v.glyphLabels.push_back({std::to_string(l.label), config::labelGlyphKind(l.kind)});
  const bool blueNoise = s.glyphMap.placement == render::GlyphPlacement::BlueNoise;
  v.glyphPlacement = blueNoise ? config::GlyphPlacement::BlueNoise : config::GlyphPlacement::Paper;
  if (blueNoise)  // the map's scale, back in mm
    v.glyphSpacingMm =
        render::blueNoiseSpacing(s.glyphMap.size) * s.glyphDiameterMm / s.glyphMap.diameter;
  if (s.functionalWindow.set()) v.functionalWindow = s.functionalWindow;
  v.light = {s.lightOffset.x, s.lightOffset.y};
  v.shells = s.shells;
  for (std::size_t k = 0; k < s.shellEnabled.size(); ++k)
    if (!s.shellEnabled[k]) v.shellsDisabled.push_back(static_cast<int>(k) + 1);
  v.depthCue = s.depthCue;
  v.gradientOpacity = s.gradientOpacity;
  v.planeOffsetMm = s.planeOffsetMm;
  v.slabMm = s.slabMm;
  v.overlay = s.overlay;
  v.segmentationOutlines = s.segmentationOutlines;
  // The functional mean only where the mode takes it, as the colour map below.
  if (!takesFusionMean(s.mode)) v.overlay.projection = FusionProjection::Max;
  v.functionalClasses = s.functionalClasses;
  // Only where the mode shows it: a saved composite view with a colormap would not load.
  v.colormap = render::showsImageColors(s) ? s.imageColors->map : ColorMap::Grey;
  v.overlayColormap = s.overlayColors ? s.overlayColors->map : ColorMap::HotMetal;
  return v;
}

}  // namespace mvw::study
