#include "RenderCommand.h"

#include "CliChecks.h"
#include "DicomOutput.h"
#include "HeadlessGl.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/Version.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/dicomout/SecondaryCapture.h"
#include "mvw/io/AtomicFile.h"
#include "mvw/io/MovieWriter.h"
#include "mvw/io/Png.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/Framing.h"
#include "mvw/render/SegmentLegend.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/study/Caption.h"
#include "mvw/study/Session.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string study;
  std::string outDir;
  mvw::study::ViewOverrides overrides;
  std::string gl;  // --gl (empty: MVW_GL, else auto)
  std::string gradient = "auto";
  DicomOutputOptions dicom;
};

std::string fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// The nearest of `path` and its parents that exists (an absolute, normalised path); the names
// of the folders still to be made on the way down to `path`, outermost last, into `missing`.
fs::path nearestExisting(const fs::path& path, std::vector<std::string>* missing = nullptr) {
  std::error_code ec;
  fs::path existing = path;
  while (!existing.empty() && existing != existing.root_path() && !fs::exists(existing, ec)) {
    if (missing && !existing.filename().empty()) missing->push_back(existing.filename().string());
    existing = existing.parent_path();
  }
  return existing;
}

// Orbit frames and movies are written into a staging folder near the output folder while they are
// rendered, and moved into place with everything else once every view has rendered, so a
// failure leaves no partial output. Removed with whatever is left in it.
class Staging {
 public:
  explicit Staging(const fs::path& outDir) {
    fs::path out = fs::absolute(outDir).lexically_normal();
    if (out.filename().empty()) out = out.parent_path();
    // In the nearest folder that exists (the same file system, so the moves are renames), so
    // a failure creates no folder on the way to the output either.
    // checkOutputFolder has made sure that this is a writable folder.
    dir_ = nearestExisting(out.parent_path()) /
           (".mvw-render-" + std::to_string(::getpid()) + "-" + out.filename().string());
  }
  ~Staging() {
    std::error_code ec;
    if (made_) fs::remove_all(dir_, ec);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  const fs::path& dir() {
    if (!made_) {
      fs::create_directory(dir_);
      made_ = true;
    }
    return dir_;
  }

 private:
  fs::path dir_;
  bool made_ = false;
};

// Everything about the output folder that can be known before rendering is said then, so a
// name the file system cannot take costs no render and creates nothing: the nearest folder
// that exists must be a writable folder, and each folder still to be made a name it can hold.
void checkOutputFolder(const fs::path& outDir) {
  const fs::path out = fs::absolute(outDir).lexically_normal();
  std::vector<std::string> toMake;
  const fs::path existing = nearestExisting(out, &toMake);
  std::error_code ec;
  if (!fs::is_directory(existing, ec))
    throw InputError(outDir, existing.string() + " is not a folder");
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    throw InputError(outDir, "the folder " + existing.string() + " is not writable");
  const long nameMax = ::pathconf(existing.c_str(), _PC_NAME_MAX);
  for (const std::string& name : toMake)
    if (nameMax > 0 && static_cast<long>(name.size()) > nameMax)
      throw InputError(outDir, "the folder name '" + name.substr(0, 40) + "...' is " +
                                   std::to_string(name.size()) +
                                   " characters, more than the file system's " +
                                   std::to_string(nameMax));
}

std::string frameName(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame-%03d.png", k);
  return buf;
}

// A view's image as the reader sees it: the render, and (annotate) its caption, orientation
// labels and scale bar, the glyph legend, the colour bar of the map shown (the overlay's, else
// the image's own over its window, in the anatomy's unit; a grey image has none) and the
// segments' legend.
struct ViewPainter {
  render::VolumeRenderer& renderer;
  const mvw::study::Session& session;
  const mvw::study::PlannedView& view;
  WindowLevel shown;
  std::string caption;
  bool overlayShown;

  render::RenderedFrame operator()(const render::RenderSettings& settings) const {
    render::RenderedFrame f = renderer.render(settings);
    if (!view.config.annotate) return f;
    const Volume* functional = session.functional();
    render::annotate(f.image, f.camera, caption);
    if (functional) {
      render::GlyphLegend legend =
          mvw::study::glyphLegend(view, functional->metadata().unit, renderer.functionalRange());
      // Glyph kinds (issue 40): each icon drawn by the view's own glyph shading.
      if (render::usesGlyphKinds(settings)) renderer.renderGlyphIcons(settings, legend);
      render::drawGlyphLegend(f.image, legend);
    }
    if (overlayShown) {
      auto [flo, fhi] = renderer.functionalRange();
      if (settings.functionalHigh > settings.functionalLow)
        flo = settings.functionalLow, fhi = settings.functionalHigh;
      const std::string name = mvw::study::volumeName(*functional, "functional");
      if (settings.overlayColors)
        render::drawColourBar(f.image, flo, fhi, functional->metadata().unit,
                              *settings.overlayColors, name);
      else
        render::drawColourBar(f.image, flo, fhi, functional->metadata().unit, name);
    } else if (render::showsImageColors(settings)) {
      render::drawColourBar(f.image, shown.level - 0.5 * shown.window,
                            shown.level + 0.5 * shown.window, session.anatomical().metadata().unit,
                            *settings.imageColors,
                            mvw::study::volumeName(session.anatomical(), "anatomical"));
    }
    const mvw::study::SegmentOverlay* segments = session.segments();
    if (segments && settings.mode == render::RenderMode::Mpr && settings.segmentOutlines) {
      std::vector<render::LegendEntry> legend;
      for (std::size_t i = 0; i < segments->names.size(); ++i)
        legend.push_back({segments->names[i], segments->colours[i]});
      render::drawSegmentLegend(f.image, legend);
    }
    return f;
  }
};

// The rest of an orbit's frames (frame 0 is the still itself, at the view's own azimuth),
// written with the movie into the staging folder; returns render.json's "orbit" record.
nlohmann::json renderOrbit(const ViewPainter& paint, const render::RenderedFrame& still,
                           Staging& staging, std::vector<Image>* keep) {
  const config::ViewConfig& c = paint.view.config;
  const fs::path folder = staging.dir() / c.name;
  fs::create_directories(folder);
  const std::string movieName = c.name + ".mp4";
  io::MovieWriter movie(staging.dir() / movieName, still.image.width, still.image.height,
                        c.orbitFps);
  const std::vector<double> azimuths = config::orbitAzimuths(c);
  nlohmann::json files = nlohmann::json::array();
  double ms = still.milliseconds;
  for (std::size_t k = 0; k < azimuths.size(); ++k) {
    render::RenderedFrame f;
    if (k == 0) {
      f.image = still.image;
    } else {
      render::RenderSettings turned = paint.view.settings;
      turned.camera.azimuthDeg = azimuths[k];
      f = paint(turned);
      ms += f.milliseconds;
    }
    const std::string name = frameName(static_cast<int>(k));
    io::writePng(f.image, folder / name);
    movie.add(f.image);
    if (keep) keep->push_back(f.image);
    files.push_back(c.name + "/" + name);
  }
  movie.finish();
  nlohmann::json r = {{"mode", config::toString(c.orbitMode)},
                      {"frames", azimuths.size()},
                      {"azimuths_deg", azimuths},
                      {"folder", c.name},
                      {"files", files},
                      {"movie", movieName},
                      {"movie_codec", "mp4v (MPEG-4 Part 2), OpenCV VideoWriter"},
                      {"movie_size", {movie.width(), movie.height()}},
                      {"fps", c.orbitFps},
                      {"ms_all_frames", ms}};
  if (c.orbitMode == config::OrbitMode::Rock) r["range_deg"] = c.orbitRangeDeg;
  return r;
}

// One view's entry in render.json: what was asked, what the defaults chose, what was shown.
nlohmann::json viewRecord(const ViewPainter& paint, const render::RenderedFrame& frame) {
  const mvw::study::PlannedView& v = paint.view;
  const mvw::study::Session& session = paint.session;
  const Volume& anatomy = session.anatomical();
  const double hi = paint.renderer.valueRange().second;
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
  r["window"] = paint.shown.window;
  r["level"] = paint.shown.level;
  r["iso"] = v.settings.isoValue;
  // An isovalue no voxel reaches draws an empty image: legitimate to ask, but said.
  if (v.settings.mode == render::RenderMode::Isosurface && v.settings.isoValue > hi) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "iso %g lies above the volume's maximum %g: the isosurface is empty",
                  v.settings.isoValue, hi);
    r["notes"].push_back(text);
    std::cerr << "mvw render: note: view '" << v.config.name << "': " << text << "\n";
  }
  // Fusion asked of a mode that cannot show it: drawn without, and said (the caption and the
  // colour bar name no fusion either).
  if (v.settings.fusion && !takesFusion(v.settings.mode)) {
    const std::string text =
        v.settings.mode == render::RenderMode::Mpr
            ? "fusion is for composite, isosurface, mip, minip and average views: an mpr view "
              "shows the functional volume as its overlay (\"overlay\")"
            : toString(v.settings.mode) +
                  " cannot fuse the functional volume (its shells are the anatomy's alone): drawn "
                  "without; fusion is for composite, isosurface, mip, minip and average views";
    r["notes"].push_back(text);
    std::cerr << "mvw render: note: view '" << v.config.name << "': " << text << "\n";
  }
  if (v.settings.glyphs)
    r["glyphs"] = {
        {"method", config::toString(v.config.glyphMethod)},
        {"convexity", config::toString(v.config.glyphConvexity)},
        {"diameter_mm", v.settings.glyphDiameterMm},
        {"spacing_mm", v.settings.glyphMap.placement == render::GlyphPlacement::BlueNoise
                           ? render::blueNoiseSpacing(v.settings.glyphMap.size) *
                                 v.settings.glyphDiameterMm / v.settings.glyphMap.diameter
                           : 0.0},
        {"count", v.config.glyphCount},
        {"seed", v.config.glyphSeed},
        {"map_size", v.config.glyphMapSize},
        {"map_diameter", v.config.glyphMapDiameter}};
  if (v.settings.glyphs && session.functional()) {
    // What the legend shows (issue 40): per entry its label, glyph kind, size and value.
    nlohmann::json entries = nlohmann::json::array();
    const render::GlyphLegend legend = mvw::study::glyphLegend(
        v, session.functional()->metadata().unit, paint.renderer.functionalRange());
    for (const render::GlyphLegendEntry& e : legend.entries) {
      nlohmann::json entry = {{"label", e.label},
                              {"kind", e.size > 0 ? glyphKindName(e.kind) : "none"},
                              {"size", e.size}};
      if (e.value) entry["value"] = *e.value;
      entries.push_back(entry);
    }
    r["glyphs"]["legend"] = {{"title", legend.title}, {"entries", entries}};
    if (!v.settings.glyphClassKinds.empty()) {
      nlohmann::json kinds = nlohmann::json::array();
      for (GlyphKind k : v.settings.glyphClassKinds) kinds.push_back(glyphKindName(k));
      r["glyphs"]["class_kinds"] = kinds;
    }
  }
  if (v.settings.functionalClasses > 0) r["functional_classes"] = v.settings.functionalClasses;
  if (v.settings.functionalHigh > v.settings.functionalLow)
    r["functional_window"] = {v.settings.functionalLow, v.settings.functionalHigh};
  const bool shellMode = isShellMode(v.settings.mode);
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
  if (render::showsImageColors(v.settings)) r["colormap"] = toString(v.settings.imageColors->map);
  r["functional_overlay"] = paint.overlayShown;
  if (session.segments() && v.settings.mode == render::RenderMode::Mpr)
    r["segment_outlines"] = session.segments()->names;
  if (paint.overlayShown) {
    r["overlay_opacity"] = v.settings.overlayOpacity;
    r["overlay_threshold"] = v.settings.overlayThreshold;
    r["overlay_colormap"] = toString(v.config.overlayColormap);
    r["functional_placement"] =
        session.placement() ? session.placement()->report["method"] : nlohmann::json("none");
  }
  r["ms_per_frame"] = frame.milliseconds;
  r["checksum_fnv1a64"] = fnv1a(frame.image.rgba);
  return r;
}

// render.json's study-wide part: the sources, what the readers decided (units, reorderings,
// the frame a 4D volume contributes), the placement, the GL that rendered.
nlohmann::json studyRecord(const mvw::study::Session& session,
                           const render::VolumeRenderer& renderer,
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

struct Output {
  std::string file;
  Image image;
  nlohmann::json record;
  std::vector<std::string> dicomFiles;  // with --dicom: the view's objects, in staging
};

// Everything is written into the staging folder before anything moves into place: a failure
// (a full disk) leaves no partial output. The moves are renames within one file system.
void writeOutputs(const fs::path& outDir, std::vector<Output>& outputs,
                  const std::vector<std::string>& orbits, nlohmann::json report, Staging& staging) {
  try {
    for (const auto& out : outputs) {
      io::writePng(out.image, staging.dir() / out.file);
      report["views"].push_back(out.record);
    }
    io::writeTextAtomically(staging.dir() / "render.json", report.dump(2) + "\n");
  } catch (const Error& e) {
    throw InputError(outDir,
                     std::string("cannot write the renders (is the disk full?): ") + e.what());
  }
  fs::create_directories(outDir);
  for (const auto& out : outputs) {
    fs::rename(staging.dir() / out.file, outDir / out.file);
    for (const std::string& name : out.dicomFiles) fs::rename(staging.dir() / name, outDir / name);
  }
  for (const std::string& name : orbits) {
    const fs::path folder = outDir / name;
    fs::remove_all(folder);  // an earlier run's frames
    fs::rename(staging.dir() / name, folder);
    fs::rename(staging.dir() / (name + ".mp4"), outDir / (name + ".mp4"));
  }
  fs::rename(staging.dir() / "render.json", outDir / "render.json");
}

// With --dicom: a view's still as a Secondary Capture and its orbit as one multi-frame SC, in
// a new series of the anatomical source's study (one series per view), written into staging.
std::vector<std::string> writeViewDicom(const mvw::study::PlannedView& v, const Image& still,
                                        const std::vector<Image>& orbit, double fps,
                                        const dicomout::DicomIdentity& id, int seriesNumber,
                                        Staging& staging) {
  const config::ViewConfig& c = v.config;
  dicomout::SeriesInfo series;
  series.seriesInstanceUid = dicomout::newUid();
  series.seriesNumber = seriesNumber;
  series.description =
      "mvw " + c.name + " (" + toString(c.mode) + ", " + config::toString(c.view) + ")";
  dicomout::CaptureInfo info;
  info.burnedInAnnotation = c.annotate;
  info.derivation = "mvw render: " + std::string(toString(c.mode)) + " of the " +
                    config::toString(c.view) + " view";
  std::vector<std::string> names{c.name + ".dcm"};
  dicomout::writeSecondaryCapture(staging.dir() / names.back(), {still}, id, series, info);
  if (!orbit.empty()) {
    info.instanceNumber = 2;
    info.frameTimeMs = 1000.0 / fps;
    info.derivation += ", orbit of " + std::to_string(orbit.size()) + " frames";
    names.push_back(c.name + "-orbit.dcm");
    dicomout::writeSecondaryCapture(staging.dir() / names.back(), orbit, id, series, info);
  }
  return names;
}

void runRender(const RenderOptions& o) {
  config::StudyConfig study = config::loadStudyConfig(o.study);
  checkOutputFolder(o.outDir);
  checkDicomOutput(o.dicom, o.dicom.dicom, o.outDir);
  mvw::study::Session session(std::move(study), o.overrides);
  // The context before the volumes: a --gl this machine cannot give fails in milliseconds.
  auto context = makeHeadlessContext(o.gl);
  session.load();
  // Before any render: a source without a DICOM identity needs one from the command line.
  std::optional<dicomout::DicomIdentity> identity;
  if (o.dicom.dicom) identity = dicomout::identityOf(session.anatomical(), o.dicom.given());
  render::VolumeRenderer renderer(*context, session.anatomical(),
                                  render::parseGradientSource(o.gradient));
  session.attach(renderer);
  const auto [lo, hi] = renderer.valueRange();
  std::vector<Output> outputs;
  Staging staging(o.outDir);
  std::vector<std::string> orbits;  // views whose frames and movie wait in staging
  int dicomObjects = 0;
  for (const mvw::study::PlannedView& v : session.views(renderer)) {
    const WindowLevel shown = windowOrFullRange(v.settings.window, v.settings.level, lo, hi);
    const ViewPainter paint{renderer,
                            session,
                            v,
                            shown,
                            mvw::study::viewCaption(v, shown),
                            render::showsFunctional(v.settings, session.functional() != nullptr)};
    render::RenderedFrame frame = paint(v.settings);
    nlohmann::json record = viewRecord(paint, frame);
    std::vector<Image> orbitFrames;
    if (v.config.orbit > 0) {
      record["orbit"] = renderOrbit(paint, frame, staging, identity ? &orbitFrames : nullptr);
      orbits.push_back(v.config.name);
    }
    std::vector<std::string> dicomFiles;
    if (identity) {
      dicomFiles = writeViewDicom(v, frame.image, orbitFrames, v.config.orbitFps, *identity,
                                  1000 + static_cast<int>(outputs.size()) + 1, staging);
      record["dicom"] = dicomFiles;
      dicomObjects += static_cast<int>(dicomFiles.size());
    }
    outputs.push_back({v.config.name + ".png", std::move(frame.image), record, dicomFiles});
    std::cerr << "rendered " << v.config.name << " (" << toString(v.config.mode) << ", "
              << config::toString(v.config.view) << ") in " << static_cast<int>(frame.milliseconds)
              << " ms\n";
  }
  writeOutputs(o.outDir, outputs, orbits, studyRecord(session, renderer, *context), staging);
  std::cout << "wrote " << outputs.size() << " view(s) and render.json to " << o.outDir << "\n";
  if (identity) {
    std::cout << "wrote " << dicomObjects << " DICOM Secondary Capture object(s) "
              << identityNote(*identity) << "\n";
    // Only once every view is rendered and every object written: exactly this run's objects.
    std::vector<fs::path> written;
    for (const Output& out : outputs)
      for (const std::string& name : out.dicomFiles) written.push_back(fs::path(o.outDir) / name);
    storeDicom(o.dicom, written, o.outDir, std::cout);
  }
}

}  // namespace

void renderStudy(const fs::path& study, const fs::path& outDir, const std::string& gl) {
  RenderOptions o;
  o.study = study.string();
  o.outDir = outDir.string();
  o.gl = gl;
  runRender(o);
}

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
  cmd->callback([o] {
    if (o->overrides.window.has_value() != o->overrides.level.has_value())
      throw InputError(o->study, "--window and --level go together");
    runRender(*o);
  });
}

}  // namespace mvw::app
