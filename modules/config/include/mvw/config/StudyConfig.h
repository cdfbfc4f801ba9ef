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

namespace mvw::config {

struct VolumeSource {
  std::filesystem::path path;
  std::string series;  // DICOM series selection: UID, number or part of the description
};

enum class FunctionalKind { Pet, Spect, Fmri, Perfusion, Dose, Labels, Other };

// One rendered view ("render": {"views": [...]}). Names of modes, standard views and presets
// are checked by the app against the renderer's lists before any GL work.
struct ViewConfig {
  std::string name;                  // output file stem; default "view<N>"
  std::string mode = "composite";    // composite | isosurface | mip | minip | average | mpr |
                                     // shells-mip | shells-sum | shells-lit
  std::string view = "anterior";     // anterior | posterior | left | right | superior | inferior
                                     // (| axial | coronal | sagittal)
  double azimuth = 0.0, elevation = 0.0, roll = 0.0;  // degrees
  double zoom = 1.0;
  bool perspective = false;
  int width = 512, height = 512;
  std::string preset;                // transfer function preset; "" = by modality
  std::array<double, 2> gradientOpacity{0.0, 0.0};  // 2D TF: opacity x smoothstep(g0, g1, |grad|)
  // Volumetric normal glyphs (composite, isosurface): {"method": "sized" | "simple",
  // "convexity": "convex" | "concave" | "both", "placement": "blue-noise" | "paper",
  // "spacing_mm" (blue-noise: glyph centre spacing), "diameter_mm" (default: blue-noise
  // 0.85 spacing, paper 6 mm), "min_size" (apparent bump radius at the window's low end, in
  // glyph radii; blue-noise only: "paper" is the paper's map and shading), "seed", and for the paper's random map "count", "map_size",
  // "map_diameter"}; the functional attribute is mapped to beta 0..1 by functional_window.
  bool glyphs = false;
  std::string glyphMethod = "sized";
  std::string glyphConvexity = "convex";
  std::string glyphPlacement = "blue-noise";
  double glyphSpacingMm = 5.0;
  double glyphMinSize = 0.6;
  double glyphDiameterMm = 0.85 * 5.0;
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
  std::string sampling = "linear";   // linear | nearest
  double stepMm = 0.0;               // 0 = half the smallest voxel spacing
  bool jitter = true;
  unsigned seed = 1;
  std::array<double, 3> background{0.0, 0.0, 0.0};
  std::array<double, 3> cropMin{0.0, 0.0, 0.0}, cropMax{1.0, 1.0, 1.0};  // fractions of the box
  bool annotate = true;
  std::array<double, 2> light{0.0, 0.0};  // light direction offset in screen terms; 0, 0: headlight
  double planeOffsetMm = 0.0;        // mpr: plane moved along the line of sight
  double slabMm = 0.0;               // mpr: thick-slab MIP thickness, 0 = single plane
  bool overlay = true;               // mpr: show the functional volume when there is one
  bool fusion = false;               // composite / isosurface: blend the functional colour in
  double overlayOpacity = 0.5;
  double overlayThreshold = 0.25;    // fraction of the functional value range
};

struct RenderConfig {
  std::vector<ViewConfig> views;  // default: one composite anterior view
};

// How the functional volume is placed on the anatomy ("registration": {...}):
//   none: by world coordinates (both in LPS mm); rigid / affine: mutual-information
//   registration when the study is opened; file: an ITK transform file (e.g. transform.tfm
//   from `mvw register`). rotation_search_deg > 0 adds a coarse rotation search.
struct RegistrationConfig {
  std::string method = "none";
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
std::string toString(FunctionalKind kind);

// The inverse of loadStudyConfig: every field written out, paths absolute, the file replaced
// atomically (temp + rename). loadStudyConfig of the result gives the same config.
void writeStudyConfig(const StudyConfig& config, const std::filesystem::path& file);

}  // namespace mvw::config
