#pragma once
// A study config (JSON) names the anatomical and functional volumes of a paired study.
// Plain structs with defaults, validated completely on load: an unknown key, a wrong type or
// a missing file is an InputError naming the config file and the key, before any heavy work.
//
//   { "name": "Cranium CT",
//     "anatomical": { "path": "../data/cranium/dicom", "series": "" },
//     "functional": { "path": "../data/pet.nii.gz", "kind": "pet" },
//     "render": { "views": [ { "name": "bone", "mode": "composite", "view": "anterior",
//                              "preset": "ct-bone", "width": 512, "height": 512 } ] } }
//
// Relative paths are relative to the config file's folder.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/RenderMode.h"

namespace mvw::config {

struct VolumeSource {
  std::filesystem::path path;
  std::string series;  // DICOM series selection: UID, number or part of the description
  // Slice distance (mm) for DICOM series that must be resampled (uneven or missing slices,
  // gantry tilt); 0: automatic. See io::ReadOptions::sliceSpacing.
  double sliceSpacingMm = 0.0;
};

enum class FunctionalKind { Pet, Spect, Fmri, Perfusion, Dose, Labels, Other };

// The standard views as radiologists name them, and the MPR planes (axial = seen from the
// feet, coronal = from the front, sagittal = from the patient's left).
enum class ViewName {
  Anterior,
  Posterior,
  Left,
  Right,
  Superior,
  Inferior,
  Axial,
  Coronal,
  Sagittal
};
enum class Sampling { Linear, Nearest };
// Volumetric normal glyphs: size control by eqs. (2)-(3) of Seipel 2007, or eq. (1) blending.
enum class GlyphMethod { Sized, Simple };
// Where glyphs sit in the normal map: a turned, jittered lattice with the spacing in mm
// (blue-noise), or the paper's 16 random glyphs of 32 voxels in 128^3 (paper).
enum class GlyphPlacement { BlueNoise, Paper };
// The glyph diameter when the view does not give one: most of the blue-noise spacing, and the
// paper map's own size on the patient.
inline constexpr double kBlueNoiseDiameterFraction = 0.85;
inline constexpr double kPaperGlyphDiameterMm = 6.0;

// One rendered view ("render": {"views": [...]}). Every default below is the one default of
// its key: the parser starts from a default-constructed ViewConfig.
struct ViewConfig {
  std::string name;  // output file stem; default "view<N>"
  RenderMode mode = RenderMode::Composite;
  ViewName view = ViewName::Anterior;
  double azimuth = 0.0, elevation = 0.0, roll = 0.0;  // degrees
  double zoom = 1.0;
  bool perspective = false;
  int width = 512, height = 512;
  std::string preset;                               // transfer function preset; "" = by modality
  std::array<double, 2> gradientOpacity{0.0, 0.0};  // 2D TF: opacity x smoothstep(g0, g1, |grad|)
  // Volumetric normal glyphs (composite, isosurface): {"method": "sized" | "simple",
  // "convexity": "convex" | "concave" | "both", "placement": "blue-noise" | "paper",
  // "spacing_mm" (blue-noise: glyph centre spacing), "diameter_mm" (default: blue-noise
  // kBlueNoiseDiameterFraction of the spacing, paper kPaperGlyphDiameterMm), "min_size"
  // (apparent bump radius at the window's low end, in glyph radii; blue-noise only: "paper" is
  // the paper's map and shading), "seed", and for the paper's random map "count", "map_size",
  // "map_diameter"}; the functional attribute is mapped to beta 0..1 by functional_window.
  bool glyphs = false;
  GlyphMethod glyphMethod = GlyphMethod::Sized;
  GlyphConvexity glyphConvexity = GlyphConvexity::Bumps;
  GlyphPlacement glyphPlacement = GlyphPlacement::BlueNoise;
  double glyphSpacingMm = 5.0;
  double glyphMinSize = 0.6;
  double glyphDiameterMm = kBlueNoiseDiameterFraction * 5.0;
  int glyphCount = 16, glyphMapSize = 128;
  double glyphMapDiameter = 32.0;
  unsigned glyphSeed = 1;
  std::optional<std::array<double, 2>> functionalWindow;  // values -> 0..1 (overlay, glyph beta)
  int functionalClasses = 0;  // labels: K > 0 gives label L the glyph size (L mod K + 1) / K
  std::optional<double> window, level;
  double iso = 300.0;
  // mip: depth cueing (Heidrich 1995) {"brightness": beta0, "amount": a, "contrast": b}.
  bool depthCue = false;
  double cueBrightness = 0.0, cueAmount = 0.0, cueContrast = 1.0;
  // shells-mip | shells-sum | shells-lit: number of isosurface shells, and ones switched off.
  int shells = 8;
  std::vector<int> shellsDisabled;
  bool shading = true;
  Sampling sampling = Sampling::Linear;
  double stepMm = 0.0;  // 0 = half the smallest voxel spacing
  bool jitter = true;
  unsigned seed = 1;
  std::array<double, 3> background{0.0, 0.0, 0.0};
  std::array<double, 3> cropMin{0.0, 0.0, 0.0}, cropMax{1.0, 1.0, 1.0};  // fractions of the box
  bool annotate = true;
  std::array<double, 2> light{0.0, 0.0};  // light offset in screen terms; 0, 0: headlight
  double planeOffsetMm = 0.0;             // mpr: plane moved along the line of sight
  double slabMm = 0.0;                    // mpr: thick-slab MIP thickness, 0 = single plane
  bool overlay = true;                    // mpr: show the functional volume when there is one
  bool fusion = false;                    // composite / isosurface: blend the functional colour in
  double overlayOpacity = 0.5;
  double overlayThreshold = 0.25;  // fraction of the functional value range
};

struct RenderConfig {
  std::vector<ViewConfig> views;  // default: one composite anterior view
};

// How the functional volume is placed on the anatomy ("registration": {...}):
//   none: by world coordinates (both in LPS mm); rigid / affine: mutual-information
//   registration when the study is opened; file: an ITK transform file (e.g. transform.tfm
//   from `mvw register`). rotation_search_deg > 0 adds a coarse rotation search.
enum class RegistrationMethod { None, Rigid, Affine, File };

struct RegistrationConfig {
  RegistrationMethod method = RegistrationMethod::None;
  std::filesystem::path transform;
  double rotationSearchDeg = 0.0;
};

struct StudyConfig {
  std::filesystem::path file;  // where it was loaded from
  std::string name;
  VolumeSource anatomical;
  std::optional<VolumeSource> functional;
  FunctionalKind functionalKind = FunctionalKind::Other;
  RegistrationConfig registration;
  RenderConfig render;
};

StudyConfig loadStudyConfig(const std::filesystem::path& file);

// One view object ("render": {"views": [...]} entry), validated as loadStudyConfig does;
// errors name `file` and `where` (e.g. "render.views[2]"); a view without a name is
// "view<index>".
ViewConfig parseViewConfig(const nlohmann::json& view, const std::filesystem::path& file,
                           const std::string& where, int index);
// The inverse of parseViewConfig: every field written out.
nlohmann::json viewConfigJson(const ViewConfig& view);
// The keys of a view object, from its field table ("glyphs" and "depth_cue" are objects).
std::vector<std::string> viewConfigKeys();
// The config's names of its enumerations, and their parsers (nullopt for an unknown name).
std::string toString(FunctionalKind kind);
std::string toString(ViewName view);
std::string toString(Sampling sampling);
std::string toString(GlyphMethod method);
std::string toString(GlyphConvexity convexity);
std::string toString(GlyphPlacement placement);
std::string toString(RegistrationMethod method);
std::optional<ViewName> parseViewName(const std::string& name);
std::optional<Sampling> parseSampling(const std::string& name);
// "view names: a, b, c" lists for messages.
std::string viewNameList();

// The inverse of loadStudyConfig: every field written out, paths absolute, the file replaced
// atomically (temp + rename). loadStudyConfig of the result gives the same config.
void writeStudyConfig(const StudyConfig& config, const std::filesystem::path& file);

}  // namespace mvw::config
