#include "RenderCommand.h"

#include "FunctionalPlacement.h"
#include "StudyVolumes.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "mvw/config/StudyConfig.h"
#include "mvw/core/Error.h"
#include "mvw/core/VesselPhantom.h"
#include "mvw/io/PngWriter.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/render/Annotations.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/VolumeRenderer.h"
#include "mvw/resampling/PetPhantom.h"
#include "mvw/resampling/Transform.h"

namespace mvw::app {

namespace {

namespace fs = std::filesystem;

struct RenderOptions {
  std::string study;
  std::string outDir;
  std::optional<std::string> mode, view, preset, sampling;
  std::optional<int> size;
  std::optional<double> azimuth, elevation, roll, zoom, window, level, iso;
  std::optional<double> cueBrightness, cueAmount, cueContrast;
  bool noAnnotate = false;
  bool perspective = false;
};

std::string defaultPreset(const Volume& v) {
  if (v.metadata().modality == "CT" || v.metadata().unit == "HU") return "ct-bone";
  if (v.metadata().modality == "PT" || v.metadata().modality == "NM") return "pet-hot-metal";
  return "mr-default";
}

std::string fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

struct PlannedView {
  config::ViewConfig config;
  render::RenderSettings settings;
  std::string presetName;
};

// Everything is validated before the volume is read or a GL context exists.
std::vector<PlannedView> plan(const config::StudyConfig& study, const RenderOptions& o) {
  std::vector<PlannedView> out;
  for (config::ViewConfig v : study.render.views) {
    if (o.mode) v.mode = *o.mode;
    if (o.view) v.view = *o.view;
    if (o.preset) v.preset = *o.preset;
    if (o.sampling) v.sampling = *o.sampling;
    if (o.size) v.width = v.height = *o.size;
    if (o.azimuth) v.azimuth = *o.azimuth;
    if (o.elevation) v.elevation = *o.elevation;
    if (o.roll) v.roll = *o.roll;
    if (o.zoom) v.zoom = *o.zoom;
    if (o.window) v.window = *o.window;
    if (o.level) v.level = *o.level;
    if (o.iso) v.iso = *o.iso;
    if (o.noAnnotate) v.annotate = false;
    if (o.cueBrightness || o.cueAmount || o.cueContrast) v.depthCue = true;
    if (o.cueBrightness) v.cueBrightness = *o.cueBrightness;
    if (o.cueAmount) v.cueAmount = *o.cueAmount;
    if (o.cueContrast) v.cueContrast = *o.cueContrast;
    if (o.perspective) v.perspective = true;
    PlannedView p;
    auto& s = p.settings;
    const auto mode = render::parseRenderMode(v.mode);
    if (!mode) throw InputError(study.file, "view '" + v.name + "': unknown mode '" + v.mode +
                                                "' (composite, isosurface, mip, minip, average, mpr, shells-mip, "
                                                "shells-sum, shells-lit)");
    const auto sv = render::parseStandardView(v.view);
    if (!sv) throw InputError(study.file, "view '" + v.name + "': unknown view '" + v.view +
                                              "' (anterior, posterior, left, right, superior, inferior, "
                                              "axial, coronal, sagittal)");
    if (v.sampling != "linear" && v.sampling != "nearest")
      throw InputError(study.file, "view '" + v.name + "': sampling must be linear or nearest");
    if (v.width < 1 || v.width > 8192 || v.height < 1 || v.height > 8192)
      throw InputError(study.file, "view '" + v.name + "': size must be 1..8192");
    if (v.window && !(*v.window > 0)) throw InputError(study.file, "view '" + v.name + "': window must be positive");
    if (!v.preset.empty()) {
      try {
        s.transfer = render::transferPreset(v.preset);
      } catch (const Error& e) {
        throw InputError(study.file, "view '" + v.name + "': " + e.what());
      }
    }
    s.mode = *mode;
    s.size = {v.width, v.height};
    s.camera.view = *sv;
    s.camera.azimuthDeg = v.azimuth;
    s.camera.elevationDeg = v.elevation;
    s.camera.rollDeg = v.roll;
    s.camera.zoom = v.zoom;
    s.camera.perspective = v.perspective;
    s.window = v.window.value_or(0.0);
    s.level = v.level.value_or(0.0);
    s.isoValue = v.iso;
    s.stepMm = v.stepMm;
    s.shading = v.shading;
    s.linear = v.sampling == "linear";
    s.jitter = v.jitter;
    s.seed = v.seed;
    s.background = {v.background[0], v.background[1], v.background[2]};
    s.cropMin = {v.cropMin[0], v.cropMin[1], v.cropMin[2]};
    s.cropMax = {v.cropMax[0], v.cropMax[1], v.cropMax[2]};
    s.glyphs = v.glyphs;
    s.glyphSizeControl = v.glyphMethod == "sized";
    s.glyphConvexity = v.glyphConvexity == "convex" ? 0 : v.glyphConvexity == "concave" ? 1 : 2;
    s.glyphDiameterMm = v.glyphDiameterMm;
    s.glyphMap = {v.glyphMapSize, v.glyphCount, v.glyphMapDiameter, v.glyphSeed};
    if (v.glyphs && !study.functional)
      throw InputError(study.file, "view '" + v.name + "': glyphs need a functional volume in the study");
    if (v.glyphs && (s.mode != render::RenderMode::Composite && s.mode != render::RenderMode::Isosurface))
      throw InputError(study.file, "view '" + v.name + "': glyphs work in composite and isosurface modes");
    if (v.functionalWindow) {
      s.functionalLow = (*v.functionalWindow)[0];
      s.functionalHigh = (*v.functionalWindow)[1];
    }
    s.lightOffset = {v.light[0], v.light[1]};
    s.shellCount = v.shells;
    if (!v.shellsDisabled.empty()) {
      s.shellEnabled.assign(static_cast<std::size_t>(v.shells), true);
      for (int k : v.shellsDisabled) s.shellEnabled[static_cast<std::size_t>(k - 1)] = false;
    }
    s.depthCue = v.depthCue;
    s.cueBrightness = v.cueBrightness;
    s.cueAmount = v.cueAmount;
    s.cueContrast = v.cueContrast;
    s.gradientOpacityLow = v.gradientOpacity[0];
    s.gradientOpacityHigh = v.gradientOpacity[1];
    s.planeOffsetMm = v.planeOffsetMm;
    s.slabMm = v.slabMm;
    s.overlay = v.overlay;
    s.fusion = v.fusion;
    s.functionalClasses = v.functionalClasses;
    if (v.fusion && !study.functional)
      throw InputError(study.file, "view '" + v.name + "': fusion needs a functional volume in the study");
    s.overlayOpacity = static_cast<float>(v.overlayOpacity);
    s.overlayThreshold = static_cast<float>(v.overlayThreshold);
    p.presetName = v.preset;
    p.config = v;
    out.push_back(std::move(p));
  }
  return out;
}

void runRender(const RenderOptions& o) {
  const config::StudyConfig study = config::loadStudyConfig(o.study);
  std::vector<PlannedView> views = plan(study, o);
  const Volume anatomy = readSource(study.anatomical);
  std::optional<Volume> functional;
  if (study.functional) functional = readSource(*study.functional);

  auto context = render::createHeadlessContext({16, 16});
  render::VolumeRenderer renderer(*context, anatomy);
  // The study's "registration" places the functional volume (none: by world coordinates).
  std::optional<FunctionalPlacement> placement;
  if (functional) {
    placement = placeFunctional(study, anatomy, *functional);
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
    if (v.presetName.empty()) {
      v.presetName = defaultPreset(anatomy);
      v.settings.transfer = render::transferPreset(v.presetName);
    }
    render::Frame frame = renderer.render(v.settings);
    const double window = v.settings.window > 0 ? v.settings.window : hi - lo;
    const double level = v.settings.window > 0 ? v.settings.level : 0.5 * (hi + lo);
    std::string caption = v.config.mode;
    if (v.settings.mode == render::RenderMode::Mpr) caption += " " + v.config.view;
    if (v.settings.mode == render::RenderMode::Mpr && v.settings.slabMm > 0)
      caption += "  slab " + std::to_string(static_cast<int>(v.settings.slabMm)) + " mm";
    if (v.settings.mode == render::RenderMode::Composite) caption += "  " + v.presetName;
    else if (v.settings.mode == render::RenderMode::Isosurface) caption += "  iso " + std::to_string(static_cast<int>(v.settings.isoValue));
    else caption += "  W " + std::to_string(static_cast<int>(window)) + " L " + std::to_string(static_cast<int>(level));
    if (v.settings.glyphs) caption += "  glyphs " + v.config.glyphMethod + " " + v.config.glyphConvexity;
    if (v.settings.fusion) caption += "  + colour fusion";
    const bool shellMode = v.settings.mode == render::RenderMode::ShellMip ||
                           v.settings.mode == render::RenderMode::ShellSum || v.settings.mode == render::RenderMode::ShellLit;
    if (shellMode) caption += "  " + std::to_string(v.settings.shellCount) + " shells";
    if ((v.settings.mode == render::RenderMode::Mip || shellMode) && v.settings.depthCue) {
      char cue[96];
      std::snprintf(cue, sizeof cue, "  depth cue b0 %.2f a %.2f b %.2f", v.settings.cueBrightness,
                    v.settings.cueAmount, v.settings.cueContrast);
      caption += cue;
    }
    const bool overlayShown =
        functional && (v.settings.mode == render::RenderMode::Mpr ? v.settings.overlay : v.settings.fusion);
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
    r["mode"] = v.config.mode;
    r["view"] = v.config.view;
    r["azimuth_deg"] = v.config.azimuth;
    r["elevation_deg"] = v.config.elevation;
    r["roll_deg"] = v.config.roll;
    r["zoom"] = v.config.zoom;
    r["perspective"] = v.config.perspective;
    r["size"] = {v.config.width, v.config.height};
    r["transfer_preset"] = v.presetName;
    if (v.settings.gradientOpacityHigh > 0)
      r["gradient_opacity"] = {v.settings.gradientOpacityLow, v.settings.gradientOpacityHigh};
    r["window"] = window;
    r["level"] = level;
    r["iso"] = v.settings.isoValue;
    if (v.settings.glyphs)
      r["glyphs"] = {{"method", v.config.glyphMethod}, {"convexity", v.config.glyphConvexity},
                     {"diameter_mm", v.config.glyphDiameterMm}, {"count", v.config.glyphCount},
                     {"seed", v.config.glyphSeed}, {"map_size", v.config.glyphMapSize},
                     {"map_diameter", v.config.glyphMapDiameter}};
    if (v.settings.functionalClasses > 0) r["functional_classes"] = v.settings.functionalClasses;
    if (v.settings.functionalHigh > v.settings.functionalLow)
      r["functional_window"] = {v.settings.functionalLow, v.settings.functionalHigh};
    if (shellMode) {
      r["shells"] = v.settings.shellCount;
      r["shells_disabled"] = v.config.shellsDisabled;
    }
    if ((v.settings.mode == render::RenderMode::Mip || shellMode) && v.settings.depthCue)
      r["depth_cue"] = {{"brightness", v.settings.cueBrightness}, {"amount", v.settings.cueAmount},
                        {"contrast", v.settings.cueContrast}};
    r["step_mm"] = v.settings.stepMm > 0 ? v.settings.stepMm : 0.5 * std::min({anatomy.spacing().x, anatomy.spacing().y, anatomy.spacing().z});
    r["sampling"] = v.config.sampling;
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
    std::cerr << "rendered " << v.config.name << " (" << v.config.mode << ", " << v.config.view << ") in "
              << static_cast<int>(frame.milliseconds) << " ms\n";
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
  report["gl_renderer"] = context->renderer();
  report["gl_version"] = context->version();
  report["mvw_version"] = "0.1.0";
  report["views"] = nlohmann::json::array();
  for (const auto& out : outputs) {
    io::writePng(out.image, fs::path(o.outDir) / out.file);
    report["views"].push_back(out.record);
  }
  const fs::path json = fs::path(o.outDir) / "render.json";
  const fs::path tmp = fs::path(o.outDir) / ".render.json.tmp";
  std::ofstream(tmp) << report.dump(2) << "\n";
  fs::rename(tmp, json);
  std::cout << "wrote " << outputs.size() << " view(s) and render.json to " << o.outDir << "\n";
}

}  // namespace

struct GlyphMapOptions {
  std::string output;
  render::GlyphMapSettings settings;
  double voxelMm = 1.0;
};

// `mvw glyphmap -o FILE`: the normal map as a 4-component float volume (RGB normal, A distance
// to the glyph centre / radius, -1 outside) for inspection in any NIfTI/MetaImage viewer.
void runGlyphMap(const GlyphMapOptions& o) {
  const render::GlyphMap map = render::makeGlyphMap(o.settings);
  Volume v({map.size, map.size, map.size}, 4, ScalarType::Float32,
           makeWorldFromIndex(glm::dvec3(0.0), glm::dvec3(o.voxelMm), glm::dmat3(1.0)));
  std::memcpy(v.data(), map.texels.data(), v.byteSize());
  v.metadata().seriesDescription = "mvw glyph normal map";
  io::writeVolume(v, o.output);
  std::cout << "wrote " << map.centres.size() << " glyphs of " << 2 * map.radius << " voxels in a " << map.size
            << "^3 map to " << o.output << "\n";
}

struct PhantomOptions {
  std::string output;
  VesselTreeSettings vessels;
};

// `mvw phantom vessels -o FILE`: the synthetic vessel tree of the depth-cued MIP tests.
void runVesselPhantom(const PhantomOptions& o) {
  const VesselTree tree = makeVesselTree(o.vessels);
  io::writeVolume(tree.volume, o.output);
  std::cout << "wrote a vessel tree of " << tree.segments.size() << " segments to " << o.output << "\n";
}

struct PetPhantomOptions {
  std::string ct, output;
  std::vector<double> rotateDeg{0, 0, 0}, shiftMm{0, 0, 0};
  unsigned seed = 1;
};

// `mvw phantom pet`: the PET-like test volume of the registration tests, as a file.
void runPetPhantom(const PetPhantomOptions& o) {
  const Volume ct = io::readVolume(o.ct);
  const resampling::PetPhantom phantom(ct);
  resampling::RigidParameters p;
  p.angles = glm::radians(glm::dvec3(o.rotateDeg[0], o.rotateDeg[1], o.rotateDeg[2]));
  p.translation = glm::dvec3(o.shiftMm[0], o.shiftMm[1], o.shiftMm[2]);
  const glm::dmat4 petFromCt = resampling::rigidMatrix(p, phantom.centre());
  Volume pet = phantom.pet(petFromCt, o.seed);
  pet.metadata().seriesDescription = "mvw PET-like phantom";
  io::writeVolume(pet, o.output);
  std::cout << "wrote a PET-like volume (" << pet.dimensions().x << " x " << pet.dimensions().y << " x "
            << pet.dimensions().z << ") to " << o.output << "\n";
}

void addRenderCommand(CLI::App& app) {
  {
    auto ph = std::make_shared<PhantomOptions>();
    CLI::App* phantom = app.add_subcommand("phantom", "Synthetic volumes with known geometry");
    phantom->require_subcommand(1);
    CLI::App* cmd = phantom->add_subcommand("vessels", "Branching tubes of decreasing radius on a dim noisy background");
    cmd->add_option("-o,--output", ph->output, "Output file (.nii, .nii.gz, .mha, .mhd)")->required();
    cmd->add_option("--size", ph->vessels.dimensions.x, "Voxels per side")->check(CLI::Range(16, 512));
    cmd->add_option("--generations", ph->vessels.generations, "Branching generations")->check(CLI::Range(1, 12));
    cmd->add_option("--seed", ph->vessels.seed, "Random seed");
    cmd->add_option("--noise", ph->vessels.noiseSigma, "Noise sigma")->check(CLI::NonNegativeNumber);
    cmd->callback([ph] {
      ph->vessels.dimensions = glm::ivec3(ph->vessels.dimensions.x);
      runVesselPhantom(*ph);
    });
    auto pet = std::make_shared<PetPhantomOptions>();
    CLI::App* petCmd = phantom->add_subcommand(
        "pet", "A PET-like volume made from a CT (uptake model, 6 mm blur, 4 mm grid, noise) under a known rigid transform");
    petCmd->add_option("--ct", pet->ct, "The CT (HU)")->required();
    petCmd->add_option("-o,--output", pet->output, "Output file")->required();
    petCmd->add_option("--rotate", pet->rotateDeg, "Rotation about x, y, z in degrees (ITK Euler order)")->expected(3);
    petCmd->add_option("--shift", pet->shiftMm, "Translation in mm")->expected(3);
    petCmd->add_option("--seed", pet->seed, "Noise seed");
    petCmd->callback([pet] { runPetPhantom(*pet); });
  }
  {
    auto g = std::make_shared<GlyphMapOptions>();
    CLI::App* cmd = app.add_subcommand("glyphmap", "Export the volumetric normal glyph map (NIfTI or MetaImage)");
    cmd->add_option("-o,--output", g->output, "Output file (.nii, .nii.gz, .mha, .mhd)")->required();
    cmd->add_option("--size", g->settings.size, "Voxels per side")->check(CLI::Range(8, 512));
    cmd->add_option("--count", g->settings.count, "Number of glyphs")->check(CLI::Range(1, 4096));
    cmd->add_option("--diameter", g->settings.diameter, "Glyph diameter in map voxels");
    cmd->add_option("--seed", g->settings.seed, "Random seed of the positions");
    cmd->add_option("--voxel-mm", g->voxelMm, "Voxel size written to the file")->check(CLI::PositiveNumber);
    cmd->callback([g] {
      try {
        runGlyphMap(*g);
      } catch (const InputError&) {
        throw;
      } catch (const Error& e) {
        throw InputError(g->output, e.what());  // impossible glyph requests are bad input
      }
    });
  }
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render the views of a study config headless (OSMesa) to PNG + render.json");
  cmd->add_option("study", o->study, "Study config (.json)")->required();
  cmd->add_option("-o,--output", o->outDir, "Output folder")->required();
  cmd->add_option("--mode", o->mode,
                  "composite | isosurface | mip | minip | average | mpr | shells-mip | shells-sum | shells-lit");
  cmd->add_option("--view", o->view,
                  "anterior | posterior | left | right | superior | inferior (MPR: axial | coronal | sagittal)");
  cmd->add_option("--preset", o->preset, "Transfer function: ct-bone, ct-skin, ct-muscle-bone, mr-default, pet-hot-metal");
  cmd->add_option("--size", o->size, "Image width and height in pixels")->check(CLI::Range(1, 8192));
  cmd->add_option("--azimuth", o->azimuth, "Degrees about the view's up axis");
  cmd->add_option("--elevation", o->elevation, "Degrees about the view's right axis");
  cmd->add_option("--roll", o->roll, "Degrees about the line of sight");
  cmd->add_option("--zoom", o->zoom, "Magnification (1 fits the volume)")->check(CLI::PositiveNumber);
  cmd->add_option("--window", o->window, "Window width for projections")->check(CLI::PositiveNumber);
  cmd->add_option("--level", o->level, "Window centre for projections");
  cmd->add_option("--iso", o->iso, "Isosurface value");
  cmd->add_option("--sampling", o->sampling, "linear | nearest");
  cmd->add_option("--cue-brightness", o->cueBrightness, "MIP depth cue: brightness beta0 (Heidrich 1995)");
  cmd->add_option("--cue-amount", o->cueAmount, "MIP depth cue: amount a (0 = none)");
  cmd->add_option("--cue-contrast", o->cueContrast, "MIP depth cue: contrast b (1 = plain MIP)");
  cmd->add_flag("--perspective", o->perspective, "Perspective instead of orthographic projection");
  cmd->add_flag("--no-annotate", o->noAnnotate, "No orientation labels, scale bar or caption");
  cmd->callback([o] {
    if (o->window.has_value() != o->level.has_value())
      throw InputError(o->study, "--window and --level go together");
    runRender(*o);
  });
}

}  // namespace mvw::app
