#pragma once
// A study config (JSON) names the anatomical and functional volumes of a paired study.
// Plain structs with defaults, validated completely on load: an unknown key, a wrong type or
// a missing file is an InputError naming the config file and the key, before any heavy work.
//
//   { "name": "Cranium CT",
//     "anatomical": { "path": "../data/cranium/dicom", "series": "" },
//     "functional": { "path": "../data/pet.nii.gz", "kind": "pet" },
//     (or from a PACS: "functional": { "pacs": "http://pacs:8042/dicom-web", "study": "1.2.3",
//                                      "series": "PT", "kind": "pet" })
//     "render": { "views": [ { "name": "bone", "mode": "composite", "view": "anterior",
//                              "preset": "ct-bone", "width": 512, "height": 512 } ] } }
//
// Relative paths are relative to the config file's folder.
#include <array>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Crop.h"
#include "mvw/core/DepthCue.h"
#include "mvw/core/Frame.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/core/GlyphStyle.h"
#include "mvw/core/GradientOpacity.h"
#include "mvw/core/Orbit.h"
#include "mvw/core/Overlay.h"
#include "mvw/core/RenderMode.h"
#include "mvw/core/WindowLevel.h"

namespace mvw::config {

struct VolumeSource {
  std::filesystem::path path;
  std::string series;  // DICOM series selection: UID, number or part of the description
  // Or a series on a PACS (issue 37): the server (http(s)://... or dicom://AET@host:port) and the
  // Study Instance UID; `series` then names the series (UID, number, modality or description)
  // and the study loader reads it from the verified cache (mvw::pacs::cachedSeries). `path`
  // stays empty.
  std::string pacs;
  std::string study;
  // What a 4D volume contributes ("frame": N or "mean"); unset: frame 0 (the anatomy), for the
  // functional volume the loader sets defaultFrame(kind). A 3D volume ignores frame 0 / mean.
  std::optional<FrameChoice> frame;
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
// Volumetric normal glyphs: how they are drawn (mvw/core/GlyphStyle.h).
using mvw::GlyphMethod;
using mvw::GlyphStyle;
// Where glyphs sit in the normal map: a turned, jittered lattice with the spacing in mm
// (blue-noise), or the paper's 16 random glyphs of 32 voxels in 128^3 (paper).
enum class GlyphPlacement { BlueNoise, Paper };
// The glyph defaults (spacing, diameter fraction, paper diameter, minimum size, DVR opacity)
// live in mvw/core/GlyphDefaults.h, shared with the renderer.
using mvw::kBlueNoiseDiameterFraction;
using mvw::kPaperGlyphDiameterMm;

// A label chosen for glyphs (issue 15 item 4): by number ("37") or by its name in the atlas's
// label table ("Hippocampus_L"), and what it gets.
// Bumps and dimples first, then None, then the other glyph kinds (mvw::GlyphKind; issue 40).
enum class LabelGlyphKind { Bumps, Dimples, None, Rings, Ridges, Cones, Crosses };
// Its config name ("bumps", ..., "none"), and back (nullopt: not a kind).
std::string toString(LabelGlyphKind kind);
std::optional<LabelGlyphKind> parseLabelGlyphKind(const std::string& name);
// The glyph kind a chosen label gets (None has none).
std::optional<GlyphKind> glyphKindOf(LabelGlyphKind kind);
LabelGlyphKind labelGlyphKind(GlyphKind kind);
struct LabelChoice {
  std::string label;
  LabelGlyphKind kind = LabelGlyphKind::Bumps;
  bool operator==(const LabelChoice&) const = default;
};
// A rotating view (mvw/core/Orbit.h).
using mvw::kMaxOrbitFrames;
using mvw::Orbit;
using mvw::OrbitMode;

// One rendered view ("render": {"views": [...]}). Every default below is the one default of
// its key: the parser starts from a default-constructed ViewConfig.
struct ViewConfig {
  std::string name;  // output file stem; default "view<N>"
  // The one view loadStudyConfig gives a config that names none (and the PACS window its
  // studies): no key of the config, never written back. Its mode, colour map and window are
  // then the modality's (study::ModalityDefaults::mode3d): a PET read alone opens as its MIP.
  bool implied = false;
  RenderMode mode = RenderMode::Composite;
  ViewName view = ViewName::Anterior;
  double azimuth = 0.0, elevation = 0.0, roll = 0.0;  // degrees
  double zoom = 1.0;
  std::array<double, 2> pan{0.0, 0.0};  // [right, up] mm the picture is moved on the screen
  bool perspective = false;
  int width = 512, height = 512;
  // Not a key: the shape (width / height) the zoom was chosen for when a command-line --size
  // gave the image another (0: width / height); see render::CameraSettings::fitAspect.
  double fitAspect = 0.0;
  std::string preset;               // transfer function preset; "" = by modality
  GradientOpacity gradientOpacity;  // 2D TF (mvw/core/GradientOpacity.h)
  // Volumetric normal glyphs (composite, isosurface): {"method": "sized" | "simple",
  // "convexity": "convex" | "concave" | "both", "placement": "blue-noise" | "paper",
  // "spacing_mm" (blue-noise: glyph centre spacing; default: the functional voxel, within what
  // the rendered scale shows and kGlyphSpacingMm), "diameter_mm" (default: blue-noise
  // kBlueNoiseDiameterFraction of the spacing, paper kPaperGlyphDiameterMm), "min_size"
  // (apparent bump radius at the window's low end, in glyph radii), "dvr_opacity" (composite:
  // the least opacity per mm a bump gives its samples; blue-noise only: "paper" is
  // the paper's map and shading), "seed", and for the paper's random map "count", "map_size",
  // "map_diameter"}; the functional attribute is mapped to beta 0..1 by functional_window.
  GlyphStyle glyphs;  // how they are drawn, the renderer's value too (mvw/core/GlyphStyle.h)
  // Where they sit, the config's form (the renderer holds the map it makes: study::planViews
  // and study::describeView convert). Empty spacing: from the functional voxel and the rendered
  // scale (study::applyGlyphScale); empty diameter: kBlueNoiseDiameterFraction of the spacing
  // (paper: kPaperGlyphDiameterMm).
  GlyphPlacement glyphPlacement = GlyphPlacement::BlueNoise;
  std::optional<double> glyphSpacingMm;
  std::optional<double> glyphDiameterMm;
  int glyphCount = 16, glyphMapSize = 128;
  double glyphMapDiameter = 32.0;
  unsigned glyphSeed = 1;
  ValueWindow functionalWindow;  // values -> 0..1 (overlay, glyph beta); unset: by kind
  int functionalClasses = 0;     // labels: K > 0 gives label L the glyph size (L mod K + 1) / K
  // glyphs.labels {"Hippocampus_L": "bumps", "38": "dimples", ...}: only these labels get
  // glyphs ("bumps" | "dimples" | "none"); names come from the atlas's label table (the
  // renderer holds the numbers: study's chosenLabels).
  std::vector<LabelChoice> glyphLabels;
  WindowLevel window;  // "window" and "level"; unset: by the modality (study::modalityDefaults)
  double iso = 300.0;
  // mip: depth cueing (Heidrich 1995) {"brightness": beta0, "amount": a, "contrast": b}.
  DepthCue depthCue;
  // shells-mip | shells-sum | shells-lit: number of isosurface shells, and ones switched off.
  int shells = 8;
  std::vector<int> shellsDisabled;
  bool shading = true;
  Sampling sampling = Sampling::Linear;
  double stepMm = 0.0;  // 0 = half the smallest voxel spacing
  bool jitter = true;
  unsigned seed = 1;
  std::array<double, 3> background{0.0, 0.0, 0.0};
  // Crop box in patient terms (mvw/core/Crop.h): "crop_min" and "crop_max" as fractions of the
  // volume's box along L, P, S, or "crop_mm": {"min": [...], "max": [...]} in LPS mm, which wins.
  Crop crop;
  // composite / isosurface with a crop: the cut face shows the anatomy under the MPR's window
  // (anatomy) or the isosurface colour / transfer function (plain).
  CutFace cutFace = CutFace::Anatomy;
  bool annotate = true;
  std::array<double, 2> light{0.0, 0.0};  // light offset in screen terms; 0, 0: headlight
  double planeOffsetMm = 0.0;             // mpr: plane moved along the line of sight
  double slabMm = 0.0;                    // mpr: thick-slab MIP thickness, 0 = single plane
  bool segmentationOutlines = true;       // mpr: outline the study's segmentation's segments
  // The functional overlay (mpr) and fusion (composite, isosurface, mip, minip, average):
  // mvw/core/Overlay.h.
  Overlay overlay;
  // Colour maps: the image of mip / minip / average / mpr views ("colormap"; grey-inverted also
  // turns the black background white), and the functional overlay or fusion
  // ("overlay_colormap").
  ColorMap colormap = ColorMap::Grey;
  ColorMap overlayColormap = ColorMap::HotMetal;
  // Rotating view (mvw/core/Orbit.h), from the view's azimuth on: written as
  // <name>/frame-000.png ... and <name>.mp4 at its frames per second. Off: a still.
  Orbit orbit;
};

// What a reader measured in `mvw view` ("measurements": {...}), saved with its state and drawn
// again when the state is opened: spherical ROIs (centre in LPS mm, radius in mm) whose
// statistics the viewer shows, and distance rulers between two points (LPS mm).
struct SphereMeasurement {
  std::array<double, 3> centre{0.0, 0.0, 0.0};
  double radiusMm = 0.0;
  bool operator==(const SphereMeasurement&) const = default;
};
struct RulerMeasurement {
  std::array<double, 3> from{0.0, 0.0, 0.0}, to{0.0, 0.0, 0.0};
  bool operator==(const RulerMeasurement&) const = default;
};
struct Measurements {
  std::vector<SphereMeasurement> spheres;
  std::vector<RulerMeasurement> rulers;
  bool operator==(const Measurements&) const = default;
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

// How `mvw view` arranges its four panes ("layout"): standard, the 3D view and the axial,
// coronal and sagittal MPR; pet-ct (issue 36 item 2), as PET/CT readers know it: the
// anatomical, the functional and the fused MPR of one plane (axial; pet-ct-coronal,
// pet-ct-sagittal) in step with one crosshair, and the functional volume's rotating MIP.
enum class ViewerLayout { Standard, PetCtAxial, PetCtCoronal, PetCtSagittal };

struct StudyConfig {
  std::filesystem::path file;  // where it was loaded from
  std::string name;
  VolumeSource anatomical;
  std::optional<VolumeSource> functional;
  FunctionalKind functionalKind = FunctionalKind::Other;
  // A segmentation (DICOM SEG, or a label volume) outlined on MPR views in its segments'
  // colours; it moves with the functional volume when it shares its frame of reference.
  std::optional<VolumeSource> segmentation;
  RegistrationConfig registration;
  RenderConfig render;
  Measurements measurements;
  ViewerLayout layout = ViewerLayout::Standard;
};

StudyConfig loadStudyConfig(const std::filesystem::path& file);
// The same from a JSON object already parsed (mvw.Study of a Python dict): `file` names it in
// messages, and its folder is where relative paths start.
StudyConfig studyConfigFromJson(const nlohmann::json& j, const std::filesystem::path& file);

// What a 4D functional volume contributes when the study does not say: the mean over the
// frames (a time series' frames are repeated measurements: the mean is the reference image
// SPM and FSL register, and the first frames of a run are often not yet at steady state),
// frame 0 for label maps (a mean of labels is no label).
FrameChoice defaultFrame(FunctionalKind kind);

// One view object ("render": {"views": [...]} entry), validated as loadStudyConfig does;
// errors name `file` and `where` (e.g. "render.views[2]"); a view without a name is
// "view<index>".
ViewConfig parseViewConfig(const nlohmann::json& view, const std::filesystem::path& file,
                           const std::string& where, int index);
// The inverse of parseViewConfig: every field written out.
nlohmann::json viewConfigJson(const ViewConfig& view);
// The keys of a view object, from its field table ("glyphs" and "depth_cue" are objects).
std::vector<std::string> viewConfigKeys();
// Every key of a study object below its top level, from the field tables ("anatomical.series",
// "registration.method", "measurements.spheres", "render.views", ...; "name" at the top).
std::vector<std::string> studyConfigKeyPaths();
// The config's names of its enumerations, and their parsers (nullopt for an unknown name).
std::string toString(FunctionalKind kind);
std::string toString(ViewName view);
std::string toString(Sampling sampling);
std::string toString(GlyphMethod method);
std::string toString(GlyphConvexity convexity);
std::string toString(GlyphPlacement placement);
std::string toString(RegistrationMethod method);
std::string toString(OrbitMode mode);
std::string toString(ViewerLayout layout);
std::optional<ViewerLayout> parseViewerLayout(const std::string& name);
std::string viewerLayoutList();  // "standard, pet-ct, ..." for messages
std::optional<OrbitMode> parseOrbitMode(const std::string& name);
std::optional<ViewName> parseViewName(const std::string& name);
std::optional<Sampling> parseSampling(const std::string& name);
// "view names: a, b, c" lists for messages.
std::string viewNameList();
// The range a view's number field takes in a config ("zoom", "depth_cue.amount"), for checking
// the same value given another way (a command-line override). A key that is not a number
// field of a view is a programming error.
std::pair<double, double> viewNumberRange(const std::string& key);

// A JSON document from `in` (the file `file`, for messages) as mvw reads its config files:
// syntax errors throw nlohmann's parse_error (callers word them), and a key that appears twice
// in one object throws InputError naming it: nlohmann would keep the last silently, so a
// config's "width": 64 could lose to a later "width": 512 without a word.
nlohmann::json parseJson(std::istream& in, const std::filesystem::path& file);

// The inverse of loadStudyConfig: every field written out, paths absolute, the file replaced
// atomically (temp + rename). loadStudyConfig of the result gives the same config.
void writeStudyConfig(const StudyConfig& config, const std::filesystem::path& file);

}  // namespace mvw::config
