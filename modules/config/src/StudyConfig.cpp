#include "mvw/config/StudyConfig.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "FieldTable.h"
#include "mvw/config/ConfigReference.h"
#include "mvw/config/ServerList.h"
#include "mvw/core/Check.h"
#include "mvw/core/Error.h"
#include "mvw/io/AtomicFile.h"

namespace mvw::config {

namespace {

namespace fs = std::filesystem;
using detail::EnumNames;
using detail::FieldTable;
using detail::Where;
using nlohmann::json;

// A view's window where it names none (study::modalityDefaults, study::applyModalityView).
constexpr const char* kDefaultWindow =
    "the anatomy's full value range; a PET or SPECT's mip and mpr views: 0-5 or 0-10 SUV, "
    "without SUV 0 to its 99.5th percentile";

// ---------------------------------------------------------------------------------------
// The names of the enumerations

const EnumNames<FunctionalKind> kKinds = {
    {FunctionalKind::Pet, "pet"},    {FunctionalKind::Spect, "spect"},
    {FunctionalKind::Fmri, "fmri"},  {FunctionalKind::Perfusion, "perfusion"},
    {FunctionalKind::Dose, "dose"},  {FunctionalKind::Labels, "labels"},
    {FunctionalKind::Other, "other"}};

const EnumNames<ViewName> kViewNames = {
    {ViewName::Anterior, "anterior"}, {ViewName::Posterior, "posterior"},
    {ViewName::Left, "left"},         {ViewName::Right, "right"},
    {ViewName::Superior, "superior"}, {ViewName::Inferior, "inferior"},
    {ViewName::Axial, "axial"},       {ViewName::Coronal, "coronal"},
    {ViewName::Sagittal, "sagittal"}};

const EnumNames<Sampling> kSamplings = {{Sampling::Linear, "linear"},
                                        {Sampling::Nearest, "nearest"}};

const EnumNames<GlyphMethod> kGlyphMethods = {{GlyphMethod::Sized, "sized"},
                                              {GlyphMethod::Simple, "simple"}};

const EnumNames<GlyphConvexity> kConvexities = {{GlyphConvexity::Bumps, "convex"},
                                                {GlyphConvexity::Dimples, "concave"},
                                                {GlyphConvexity::Both, "both"}};

const EnumNames<GlyphPlacement> kPlacements = {{GlyphPlacement::BlueNoise, "blue-noise"},
                                               {GlyphPlacement::Paper, "paper"}};

const EnumNames<RegistrationMethod> kRegistrations = {{RegistrationMethod::None, "none"},
                                                      {RegistrationMethod::Rigid, "rigid"},
                                                      {RegistrationMethod::Affine, "affine"},
                                                      {RegistrationMethod::File, "file"}};

const EnumNames<FusionProjection> kFusionProjections = {{FusionProjection::Max, "max"},
                                                        {FusionProjection::Mean, "mean"}};
const EnumNames<CutFace> kCutFaces = {{CutFace::Anatomy, "anatomy"}, {CutFace::Plain, "plain"}};
const EnumNames<ViewerLayout> kLayouts = {{ViewerLayout::Standard, "standard"},
                                          {ViewerLayout::PetCtAxial, "pet-ct"},
                                          {ViewerLayout::PetCtCoronal, "pet-ct-coronal"},
                                          {ViewerLayout::PetCtSagittal, "pet-ct-sagittal"}};

const EnumNames<OrbitMode> kOrbitModes = {{OrbitMode::Spin, "spin"}, {OrbitMode::Rock, "rock"}};

EnumNames<ColorMap> colorMaps() {
  EnumNames<ColorMap> names;
  static const std::vector<std::string> kNames = colorMapNames();
  for (const std::string& n : kNames) names.push_back({*parseColorMap(n), n.c_str()});
  return names;
}

EnumNames<RenderMode> renderModes() {
  EnumNames<RenderMode> names;
  static const std::vector<std::string> kNames = renderModeNames();
  for (const std::string& n : kNames) names.push_back({*parseRenderMode(n), n.c_str()});
  return names;
}

constexpr double kMaxSeed = 4294967295.0;

// A [low, high] pair with minLow <= low < high; `what` describes it in the message.
std::array<double, 2> readOrderedPair(const json& v, const Where& w, double minLow,
                                      const char* what) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() ||
      !(v[0].get<double>() >= minLow && v[0].get<double>() < v[1].get<double>()))
    w.bad(std::string("must be ") + what);
  return {v[0].get<double>(), v[1].get<double>()};
}

// A path in the config: relative ones are relative to the config file's folder.
fs::path resolvePath(const std::string& path, const fs::path& configFile) {
  const fs::path p(path);
  return (p.is_absolute() ? p : configFile.parent_path() / p).lexically_normal();
}

// How the writer stores paths: absolute, so the written config works from any folder.
std::string absolutePath(const fs::path& path) {
  return fs::absolute(path).lexically_normal().string();
}

// ---------------------------------------------------------------------------------------
// The tables

// How glyphs are drawn (mvw/core/GlyphStyle.h), the renderer's value too; its keys sit in the
// glyph object among the map's (glyphTable).
const FieldTable<GlyphStyle>& glyphStyleTable() {
  static const FieldTable<GlyphStyle> t = [] {
    FieldTable<GlyphStyle> g;
    g.enumeration("method",
                  "Size control: sized, eqs. (2)-(3) of Seipel 2007; simple, eq. (1) blending.",
                  &GlyphStyle::method, kGlyphMethods)
        .enumeration("convexity", "Bumps (convex), dimples (concave) or both.",
                     &GlyphStyle::convexity, kConvexities)
        .number("min_size", "Apparent bump radius at the window's low end, in glyph radii.",
                &GlyphStyle::minSize, 0.0, 1.0)
        .number("dvr_opacity",
                "Composite, blue-noise: the least opacity per mm of ray a bump gives its samples.",
                &GlyphStyle::dvrOpacity, 0.0, 1.0)
        .boolean("on_surface",
                 "Glyph kinds, orthographic views: the glyphs on the visible surface, a lattice on "
                 "the image, each shape whole on the disc facing the viewer (issue 52); false, a "
                 "3D lattice the surface cuts. They keep to the image when the view turns.",
                 &GlyphStyle::onSurface)
        .add(
            "class_kinds",
            "Glyph kind per class: with functional_classes, of each label class in class "
            "order (the last one past the list's end); else the window cut into equal ranges, "
            "one kind each.",
            {"array",
             "\"bumps\" | \"dimples\" | \"rings\" | \"ridges\" | \"cones\" | "
             "\"crosses\"",
             "every class bumps",
             {}},
            [](const json& v, GlyphStyle& out, const Where& w) {
              if (!v.is_array() || v.empty())
                w.bad(
                    "must be a non-empty array of glyph kinds (bumps, dimples, rings, ridges, "
                    "cones, crosses)");
              out.classKinds.clear();
              for (std::size_t i = 0; i < v.size(); ++i) {
                const Where item{w.file, w.key + "[" + std::to_string(i) + "]"};
                const std::optional<GlyphKind> k = parseGlyphKind(readString(v[i], item));
                if (!k) item.bad("must be bumps, dimples, rings, ridges, cones or crosses");
                out.classKinds.push_back(*k);
              }
            },
            [](const GlyphStyle& in, json& j, const char* k) {
              if (in.classKinds.empty()) return;
              json a = json::array();
              for (GlyphKind c : in.classKinds) a.push_back(glyphKindName(c));
              j[k] = a;
            });
    return g;
  }();
  return t;
}

// The glyph object: the style's keys (glyphStyleTable) at their places among the config's form
// of the map (placement, spacing, diameter, the paper map's) and the chosen labels, which the
// renderer holds in its own form (study::planViews converts).
const FieldTable<ViewConfig>& glyphTable() {
  static const FieldTable<ViewConfig> t = [] {
    using V = ViewConfig;
    const FieldTable<GlyphStyle>& style = glyphStyleTable();
    FieldTable<ViewConfig> g;
    g.inlined(&V::glyphs, style, {"method", "convexity"})
        .enumeration("placement",
                     "Where glyphs sit: blue-noise, a turned, jittered lattice spacing_mm apart; "
                     "paper, the paper's 16 random glyphs of 32 voxels in 128^3.",
                     &ViewConfig::glyphPlacement, kPlacements)
        .optionalNumber("spacing_mm", "Blue-noise: the glyph centres' spacing in mm.",
                        &ViewConfig::glyphSpacingMm, 0.5, 1000.0)
        .whenAbsent("the functional voxel, within what the rendered scale shows")
        .inlined(&V::glyphs, style, {"min_size", "dvr_opacity", "on_surface"})
        .optionalNumber("diameter_mm", "Glyph diameter in mm.", &ViewConfig::glyphDiameterMm, 0.1,
                        1000.0)
        .whenAbsent("blue-noise: a fraction of the spacing; paper: the paper's diameter")
        .number("count", "Paper: the number of random glyphs in the map.", &ViewConfig::glyphCount,
                1, 255)
        .number("seed", "Seed of the glyph placement.", &ViewConfig::glyphSeed, 0, kMaxSeed)
        .number("map_size", "Paper: the glyph map's size in voxels per side.",
                &ViewConfig::glyphMapSize, 8, 512)
        .number("map_diameter", "Paper: the glyph diameter in map voxels.",
                &ViewConfig::glyphMapDiameter, 2, 256)
        .add(
            "labels",
            "Label maps: only these labels get glyphs, by number (\"38\") or by name in the "
            "atlas's label table (\"Hippocampus_L\").",
            {"object",
             "label: \"bumps\", \"dimples\", \"rings\", \"ridges\", \"cones\", "
             "\"crosses\" or \"none\"",
             "every label",
             {}},
            [](const json& v, ViewConfig& out, const Where& w) {
              if (!v.is_object() || v.empty())
                w.bad(
                    "must be an object of labels (number or name) and a glyph kind (bumps, "
                    "dimples, rings, ridges, cones, crosses) or \"none\"");
              out.glyphLabels.clear();
              for (const auto& [label, kind] : v.items()) {
                const Where item{w.file, w.key + "." + label};
                const std::optional<LabelGlyphKind> k = parseLabelGlyphKind(readString(kind, item));
                if (!k)
                  item.bad(
                      "must be \"bumps\", \"dimples\", \"rings\", \"ridges\", \"cones\", "
                      "\"crosses\" or \"none\"");
                out.glyphLabels.push_back({label, *k});
              }
            },
            [](const ViewConfig& in, json& j, const char* k) {
              if (in.glyphLabels.empty()) return;
              json o = json::object();
              for (const LabelChoice& c : in.glyphLabels) o[c.label] = toString(c.kind);
              j[k] = o;
            })
        .inlined(&V::glyphs, style, {"class_kinds"});
    if (!g.coveredKeys(style)) throw std::logic_error("a glyph style key is not in glyphs");
    return g;
  }();
  return t;
}

// The depth cue (mvw/core/DepthCue.h), the renderer's value too.
const FieldTable<DepthCue>& depthCueTable() {
  static const FieldTable<DepthCue> t = [] {
    FieldTable<DepthCue> c;
    c.number("brightness", "Brightness beta0.", &DepthCue::brightness, 0.0, 10.0)
        .number("amount", "Amount a (0: no cueing).", &DepthCue::amount, -10.0, 10.0)
        .number("contrast", "Contrast b (1: plain MIP).", &DepthCue::contrast, 0.0, 10.0);
    return c;
  }();
  return t;
}

// A point in LPS mm as the config writes it.
std::array<double, 3> lpsArray(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

// The crop (mvw/core/Crop.h), the renderer's value too; its keys sit in the view object.
const FieldTable<Crop>& cropTable() {
  static const FieldTable<Crop> t = [] {
    FieldTable<Crop> crop;
    crop.numbers("crop_min",
                 "Crop box's low corner as fractions of the volume's box along L, P, S (0: most "
                 "right, anterior, inferior).",
                 &Crop::min, 0.0, 1.0)
        .numbers("crop_max",
                 "Crop box's high corner as fractions of the volume's box along L, P, S (1: most "
                 "left, posterior, superior).",
                 &Crop::max, 0.0, 1.0)
        .add(
            "crop_mm", "Crop box in LPS mm; wins over crop_min and crop_max.",
            {"object", "{\"min\": [L, P, S], \"max\": [L, P, S]}, min < max, within +-1e6", "", {}},
            [](const json& c, Crop& out, const Where& w) {
              const std::string what =
                  "must be {\"min\": [L, P, S], \"max\": [L, P, S]} in LPS mm, min < max";
              if (!c.is_object() || c.size() != 2 || !c.contains("min") || !c.contains("max"))
                w.bad(what);
              std::array<std::array<double, 3>, 2> box{};
              for (int m = 0; m < 2; ++m) {
                const json& a = c[m == 0 ? "min" : "max"];
                if (!a.is_array() || a.size() != 3) w.bad(what);
                for (std::size_t i = 0; i < 3; ++i) {
                  if (!a[i].is_number() || !(std::abs(a[i].get<double>()) <= 1e6)) w.bad(what);
                  box[static_cast<std::size_t>(m)][i] = a[i].get<double>();
                }
              }
              for (std::size_t i = 0; i < 3; ++i)
                if (!(box[0][i] < box[1][i])) w.bad(what);
              out.minMm = glm::dvec3(box[0][0], box[0][1], box[0][2]);
              out.maxMm = glm::dvec3(box[1][0], box[1][1], box[1][2]);
            },
            [](const Crop& in, json& j, const char* k) {
              if (in.minMm && in.maxMm)
                j[k] = {{"min", lpsArray(*in.minMm)}, {"max", lpsArray(*in.maxMm)}};
            });
    return crop;
  }();
  return t;
}

// The functional overlay and fusion (mvw/core/Overlay.h), the renderer's value too; its keys
// sit in the view object.
const FieldTable<Overlay>& overlayTable() {
  static const FieldTable<Overlay> t = [] {
    FieldTable<Overlay> o;
    o.boolean("overlay", "MPR: show the functional volume, where the study has one.", &Overlay::mpr)
        .boolean("fusion",
                 "Composite and isosurface: blend the functional colour in; mip, minip and "
                 "average: the functional volume's projection along each ray in the overlay "
                 "colour map over the anatomy's.",
                 &Overlay::fusion)
        .enumeration("fusion_projection",
                     "Fused minip and average views: the functional projection along each ray, "
                     "the maximum of its samples or their mean (a fused mip takes the maximum).",
                     &Overlay::projection, kFusionProjections)
        .number("overlay_opacity", "Opacity of the functional overlay.", &Overlay::opacity, 0.0,
                1.0)
        .number("overlay_threshold",
                "Functional values below this fraction of their range are not overlaid.",
                &Overlay::threshold, 0.0, 1.0);
    return o;
  }();
  return t;
}

// The anatomy's window (mvw/core/WindowLevel.h): both keys or neither (parseViewConfig), written
// only while it is set.
const FieldTable<WindowLevel>& windowLevelTable() {
  static const FieldTable<WindowLevel> t = [] {
    const auto set = [](const WindowLevel& w) { return w.set(); };
    FieldTable<WindowLevel> w;
    w.number("window", "Window width, in the anatomy's unit (goes with level).",
             &WindowLevel::window, 1e-9, 1e12)
        .writtenWhen(set)
        .whenAbsent(kDefaultWindow)
        .number("level", "Window centre, in the anatomy's unit (goes with window).",
                &WindowLevel::level, -1e12, 1e12)
        .writtenWhen(set)
        .whenAbsent(kDefaultWindow);
    return w;
  }();
  return t;
}

// A rotating view (mvw/core/Orbit.h): its frames' key switches it on.
const FieldTable<Orbit>& orbitTable() {
  static const FieldTable<Orbit> t = [] {
    FieldTable<Orbit> o;
    o.add(
         "orbit",
         "A rotating view: this many frames about the patient's long axis from the view's "
         "azimuth on.",
         {"integer", "2 .. " + std::to_string(kMaxOrbitFrames), "a still", {}},
         [](const json& n, Orbit& out, const Where& w) {
           if (!n.is_number_integer() || n.get<long long>() < 2 ||
               n.get<long long>() > kMaxOrbitFrames)
             w.bad("must be a whole number of frames, 2.." + std::to_string(kMaxOrbitFrames));
           out.frames = n.get<int>();
         },
         [](const Orbit& in, json& j, const char* k) {
           if (in.on()) j[k] = in.frames;
         })
        .enumeration("orbit_mode",
                     "spin: a full turn (azimuth + 360 k / N); rock: back and forth (azimuth + "
                     "orbit_range sin(2 pi k / N)).",
                     &Orbit::mode, kOrbitModes)
        .number("orbit_range", "rock: how far the view swings each way, in degrees.",
                &Orbit::rangeDeg, 1.0, 180.0)
        .number("orbit_fps", "Frames per second of the orbit's movie.", &Orbit::fps, 1.0, 60.0);
    return o;
  }();
  return t;
}

const FieldTable<ViewConfig>& viewTable() {
  static const FieldTable<ViewConfig> t = [] {
    using V = ViewConfig;
    FieldTable<V> v;
    v.string("name",
             "The output's name: NAME.png (an orbit: NAME/frame-000.png ... and NAME.mp4); a "
             "plain file name of at most 120 characters.",
             &V::name)
        .whenAbsent("view<N>, N its place in views from 0")
        .enumeration("mode", "How the view renders the volume.", &V::mode, renderModes())
        .enumeration("view",
                     "The direction it is seen from as radiologists name it, or an MPR plane "
                     "(axial: seen from the feet, coronal: from the front, sagittal: from the "
                     "patient's left).",
                     &V::view, kViewNames)
        .number("azimuth", "Degrees about the view's up axis.", &V::azimuth, -3600, 3600)
        .number("elevation", "Degrees about the view's right axis.", &V::elevation, -3600, 3600)
        .number("roll", "Degrees about the line of sight.", &V::roll, -3600, 3600)
        .number("zoom", "Magnification (1 fits the volume).", &V::zoom, 1e-3, 1e3)
        .numbers("pan", "Picture moved on the screen [right, up] in mm (after the zoom).", &V::pan,
                 -1e6, 1e6)
        .boolean("perspective", "Perspective instead of orthographic projection.", &V::perspective)
        .number("width", "Image width in pixels.", &V::width, 1, 8192)
        .number("height", "Image height in pixels.", &V::height, 1, 8192)
        .string("preset", "Transfer function preset by name (ct-bone, ct-skin, mr-default, ...).",
                &V::preset)
        .whenAbsent("chosen by the anatomy's modality")
        .inlined(&V::window, windowLevelTable())
        .number("iso", "Isosurface value, in the anatomy's unit.", &V::iso, -1e12, 1e12)
        .boolean("shading", "Gradient shading.", &V::shading)
        .enumeration("sampling", "How the volume is sampled between voxels.", &V::sampling,
                     kSamplings)
        .number("step_mm",
                "Distance between samples along a ray in mm (0: half the smallest "
                "voxel spacing).",
                &V::stepMm, 0.0, 100.0)
        .boolean("jitter", "Jitter each ray's first sample (no wood-grain rings).", &V::jitter)
        .number("seed", "Seed of the ray jitter.", &V::seed, 0, kMaxSeed)
        .numbers("background", "Background colour [red, green, blue].", &V::background, 0.0, 1.0)
        .inlined(&V::crop, cropTable())
        .enumeration("cut_face",
                     "Composite and isosurface with a crop: the cut face shows the anatomy's grey "
                     "values under the MPR window (window / level), glyphs and fusion on it "
                     "(anatomy), or the isosurface colour and the transfer function (plain).",
                     &V::cutFace, kCutFaces)
        .boolean("annotate", "Orientation labels, scale bar, caption and colour bar.", &V::annotate)
        .add(
            "light", "Light offset in screen terms ([0, 0]: a headlight).",
            {"array of 2 numbers", "[right, up]", "", {}},
            [](const json& l, V& out, const Where& w) {
              if (!l.is_array() || l.size() != 2 || !l[0].is_number() || !l[1].is_number())
                w.bad("must be [right, up] (0, 0 is a headlight)");
              out.light = {l[0].get<double>(), l[1].get<double>()};
            },
            [](const V& in, json& j, const char* k) { j[k] = in.light; })
        .section("glyphs",
                 "Volumetric normal glyphs showing the functional volume (composite, "
                 "isosurface): on where present.",
                 &V::glyphs, &GlyphStyle::on, glyphTable())
        .add(
            "functional_window",
            "Functional values mapped to 0 .. 1 (overlay, glyph size) [low, high].",
            {"array of 2 numbers", "low < high", "by the functional volume's kind", {}},
            [](const json& fw, V& out, const Where& w) {
              const auto [low, high] = readOrderedPair(fw, w, -std::numeric_limits<double>::max(),
                                                       "[low, high] with low < high");
              out.functionalWindow = {low, high};
            },
            [](const V& in, json& j, const char* k) {
              if (in.functionalWindow.set())
                j[k] = std::array<double, 2>{in.functionalWindow.low, in.functionalWindow.high};
            })
        .section("depth_cue", "MIP depth cueing (Heidrich 1995): on where present.", &V::depthCue,
                 &DepthCue::on, depthCueTable())
        .add(
            "gradient_opacity",
            "2D transfer function: opacity times smoothstep(low, high, |gradient|), in the "
            "anatomy's unit per mm.",
            {"array of 2 numbers", "0 <= low < high", "off", {}},
            [](const json& g, V& out, const Where& w) {
              const auto [low, high] =
                  readOrderedPair(g, w, 0.0, "[low, high] with 0 <= low < high (unit/mm)");
              out.gradientOpacity = {low, high};
            },
            [](const V& in, json& j, const char* k) {
              if (in.gradientOpacity.on())
                j[k] = std::array<double, 2>{in.gradientOpacity.low, in.gradientOpacity.high};
            })
        .number("plane_offset_mm", "MPR: the plane moved along the line of sight, in mm.",
                &V::planeOffsetMm, -1e4, 1e4)
        .number("slab_mm", "MPR: thick-slab MIP thickness in mm (0: a single plane).", &V::slabMm,
                0.0, 1e4)
        .inlined(&V::overlay, overlayTable())
        .boolean("segmentation_outlines", "MPR: outline the segments of the study's segmentation.",
                 &V::segmentationOutlines)
        .number("shells", "shells-mip, shells-sum, shells-lit: the number of isosurface shells.",
                &V::shells, 1, 256)
        .add(
            "shells_disabled", "Shells switched off, by number (1 is the first).",
            {"array of integers", "1 .. shells", "", {}},
            [](const json& d, V& out, const Where& w) {
              if (!d.is_array()) w.bad("must be an array of shell numbers");
              out.shellsDisabled.clear();
              for (const auto& e : d) {
                if (!e.is_number_integer() || e.get<long long>() < 1 || e.get<long long>() > 256)
                  w.bad("holds shell numbers 1.." + std::to_string(out.shells));
                out.shellsDisabled.push_back(e.get<int>());
              }
            },
            [](const V& in, json& j, const char* k) { j[k] = in.shellsDisabled; })
        .number("functional_classes",
                "Label maps: K > 0 gives label L the glyph size (L mod K + 1) / K (0: off).",
                &V::functionalClasses, 0, 64)
        .enumeration("colormap",
                     "Colour map of mip, minip, average and mpr images (grey-inverted also turns "
                     "the black background white).",
                     &V::colormap, colorMaps())
        .enumeration("overlay_colormap", "Colour map of the functional overlay and fusion.",
                     &V::overlayColormap, colorMaps())
        .inlined(&V::orbit, orbitTable());
    return v;
  }();
  return t;
}

}  // namespace

ViewConfig parseViewConfig(const json& j, const fs::path& file, const std::string& where,
                           int index) {
  ViewConfig v;
  viewTable().read(j, v, Where{file, where + "."});
  const std::string w = where + ".";
  if (v.name.empty()) v.name = "view" + std::to_string(index);
  if (v.name.find_first_of("/\\") != std::string::npos || v.name == "." || v.name == "..")
    throw InputError(file, "'" + w + "name' must be a plain file name");
  // It names files (NAME.png, an orbit's NAME/ and NAME.mp4): printable, and short enough
  // for any file system's 255-byte names.
  if (v.name.size() > 120)
    throw InputError(
        file, "'" + w + "name' is " + std::to_string(v.name.size()) + " characters; at most 120");
  for (unsigned char c : v.name)
    if (c < 0x20 || c == 0x7f) throw InputError(file, "'" + w + "name' holds a control character");
  if (j.contains("window") != j.contains("level"))
    throw InputError(file, "'" + w + "window' and '" + w + "level' go together");
  for (int a = 0; a < 3; ++a)
    if (v.crop.min[a] >= v.crop.max[a])
      throw InputError(file, "'" + w + "crop_min' must be below 'crop_max'");
  if (v.colormap != ColorMap::Grey && !takesImageColors(v.mode))
    throw InputError(
        file, "'" + w + "colormap' applies to mip, minip, average and mpr views, not " +
                  toString(v.mode) + " (the functional overlay's is '" + w + "overlay_colormap')");
  if (v.orbit.on() &&
      (v.view == ViewName::Superior || v.view == ViewName::Inferior || v.view == ViewName::Axial))
    throw InputError(file, "'" + w + "orbit' turns about the patient's long axis, which view '" +
                               toString(v.view) +
                               "' looks along: use anterior, posterior, left, right, coronal "
                               "or sagittal");
  for (int k : v.shellsDisabled)
    if (k > v.shells)
      throw InputError(
          file, "'" + w + "shells_disabled' holds shell numbers 1.." + std::to_string(v.shells));
  return v;
}

json viewConfigJson(const ViewConfig& v) { return viewTable().write(v); }

std::string toString(OrbitMode mode) { return detail::nameOf(kOrbitModes, mode); }

std::string toString(LabelGlyphKind kind) {
  const std::optional<GlyphKind> g = glyphKindOf(kind);
  return g ? glyphKindName(*g) : "none";
}

std::optional<LabelGlyphKind> parseLabelGlyphKind(const std::string& name) {
  if (name == "none") return LabelGlyphKind::None;
  const std::optional<GlyphKind> g = parseGlyphKind(name);
  if (!g) return std::nullopt;
  return labelGlyphKind(*g);
}

std::optional<GlyphKind> glyphKindOf(LabelGlyphKind kind) {
  switch (kind) {
    case LabelGlyphKind::Bumps:
      return GlyphKind::Bumps;
    case LabelGlyphKind::Dimples:
      return GlyphKind::Dimples;
    case LabelGlyphKind::Rings:
      return GlyphKind::Rings;
    case LabelGlyphKind::Ridges:
      return GlyphKind::Ridges;
    case LabelGlyphKind::Cones:
      return GlyphKind::Cones;
    case LabelGlyphKind::Crosses:
      return GlyphKind::Crosses;
    case LabelGlyphKind::None:
      break;
  }
  return std::nullopt;
}

LabelGlyphKind labelGlyphKind(GlyphKind kind) {
  switch (kind) {
    case GlyphKind::Bumps:
      return LabelGlyphKind::Bumps;
    case GlyphKind::Dimples:
      return LabelGlyphKind::Dimples;
    case GlyphKind::Rings:
      return LabelGlyphKind::Rings;
    case GlyphKind::Ridges:
      return LabelGlyphKind::Ridges;
    case GlyphKind::Cones:
      return LabelGlyphKind::Cones;
    case GlyphKind::Crosses:
      return LabelGlyphKind::Crosses;
  }
  return LabelGlyphKind::None;
}
std::string toString(ViewerLayout layout) { return detail::nameOf(kLayouts, layout); }

std::optional<ViewerLayout> parseViewerLayout(const std::string& name) {
  return detail::parseName(kLayouts, name);
}

std::string viewerLayoutList() { return detail::namesOf(kLayouts); }

std::optional<OrbitMode> parseOrbitMode(const std::string& name) {
  return detail::parseName(kOrbitModes, name);
}

std::vector<std::string> viewConfigKeys() { return viewTable().keys(); }

namespace {

// A volume source as the file has it: the path relative to the config's folder, and for the
// functional volume its kind.
struct SourceEntry {
  VolumeSource source;
  FunctionalKind kind = FunctionalKind::Other;
};

FieldTable<SourceEntry> sourceTable(bool withKind) {
  FieldTable<SourceEntry> t;
  t.add(
       "path",
       "The volume: a NIfTI, MetaImage or DICOM file, or a DICOM folder; relative to the "
       "config file's folder.",
       {"string", "an existing file or folder", "required (or \"pacs\")", {}},
       [](const json& v, SourceEntry& out, const Where& w) {
         const std::string p = detail::readString(v, w);
         if (p.empty()) w.bad("is empty");
         out.source.path = resolvePath(p, w.file);
         std::error_code ec;
         if (!fs::exists(out.source.path, ec))
           w.bad("names " + out.source.path.string() + ", which does not exist");
       },
       [](const SourceEntry& in, json& j, const char* k) {
         if (!in.source.path.empty()) j[k] = absolutePath(in.source.path);
       })
      .add(
          "pacs",
          "Instead of a path, a PACS: http(s)://host:port/PATH (DICOMweb), "
          "dicom://AET@host:port (DIMSE) or the name of a server saved in servers.json; the "
          "series is read from the verified cache.",
          {"string", "a server URL (no credentials) or a saved server's name", "", {}},
          [](const json& v, SourceEntry& out, const Where& w) {
            const std::string p = detail::readString(v, w);
            if (!p.empty() && isServerName(p)) {
              // Known now, so a misspelt name is said with the config's file and key.
              try {
                resolveServer(p);
              } catch (const InputError& e) {
                if (e.file() != p) throw;  // the server list itself is bad: it names itself
                w.bad(e.problem());
              }
              out.source.pacs = p;
              return;
            }
            if (p.rfind("http://", 0) != 0 && p.rfind("https://", 0) != 0 &&
                p.rfind("dicom://", 0) != 0)
              w.bad("must be http(s)://host:port/PATH or dicom://AET@host:port");
            if (p.rfind("http", 0) == 0 && p.find('@') != std::string::npos)
              w.bad("must not hold credentials: set MVW_PACS_USER and MVW_PACS_PASSWORD");
            out.source.pacs = p;
          },
          [](const SourceEntry& in, json& j, const char* k) {
            if (!in.source.pacs.empty()) j[k] = in.source.pacs;
          })
      .add(
          "study", "With \"pacs\": the Study Instance UID.", {"string", "a DICOM UID", "", {}},
          [](const json& v, SourceEntry& out, const Where& w) {
            const std::string uid = detail::readString(v, w);
            const bool digitsAndDots = uid.find_first_not_of("0123456789.") == std::string::npos;
            if (uid.empty() || uid.size() > 64 || !digitsAndDots || uid.front() == '.' ||
                uid.back() == '.' || uid.find("..") != std::string::npos)
              w.bad("must be a DICOM UID (digits and dots, at most 64 characters)");
            out.source.study = uid;
          },
          [](const SourceEntry& in, json& j, const char* k) {
            if (!in.source.study.empty()) j[k] = in.source.study;
          })
      .add(
          "series",
          "The DICOM series, where the folder holds several: its UID, number or part of its "
          "description.",
          {"string", "", "", {}},
          [](const json& v, SourceEntry& out, const Where& w) {
            out.source.series = detail::readString(v, w);
          },
          [](const SourceEntry& in, json& j, const char* k) {
            if (!in.source.series.empty()) j[k] = in.source.series;
          })
      .add(
          "frame", "What a 4D volume contributes: one frame, or the mean over the frames.",
          {"integer or string",
           "0, 1, ... or \"mean\"",
           withKind ? "\"mean\"; kind labels: 0" : "0",
           {}},
          [](const json& v, SourceEntry& out, const Where& w) {
            std::optional<FrameChoice> f;
            if (v.is_number_integer() && v.get<long long>() >= 0 && v.get<long long>() < 1000000)
              f = FrameChoice{false, v.get<int>()};
            else if (v.is_string())
              f = parseFrameChoice(v.get<std::string>());
            if (!f || (!f->mean && v.is_string()))
              w.bad("must be a frame number (0, 1, ...) or \"mean\"");
            out.source.frame = f;
          },
          [](const SourceEntry& in, json& j, const char* k) {
            if (!in.source.frame) return;
            if (in.source.frame->mean)
              j[k] = "mean";
            else
              j[k] = in.source.frame->index;
          })
      .add(
          "slice_spacing_mm",
          "Slice distance in mm for DICOM series that must be resampled (uneven or missing "
          "slices, gantry tilt).",
          {"number", "0 .. 1000", "0: automatic", {}},
          [](const json& v, SourceEntry& out, const Where& w) {
            out.source.sliceSpacingMm = detail::readNumber(v, w, 0.0, 1000.0);
          },
          [](const SourceEntry& in, json& j, const char* k) {
            if (in.source.sliceSpacingMm > 0) j[k] = in.source.sliceSpacingMm;
          });
  if (withKind)
    t.enumeration("kind",
                  "What the functional volume measures: its display defaults (colours, window) "
                  "and the frame a 4D one contributes.",
                  &SourceEntry::kind, kKinds);
  return t;
}

SourceEntry readSource(const json& j, const fs::path& file, const std::string& name,
                       bool withKind) {
  if (!j.is_object()) throw InputError(file, "'" + name + "' must be an object with a \"path\"");
  SourceEntry e;
  sourceTable(withKind).read(j, e, Where{file, name + "."});
  const bool pacs = j.contains("pacs");
  if (pacs && j.contains("path"))
    throw InputError(file, "'" + name + "' names both a \"path\" and a \"pacs\": give one");
  if (pacs && (!j.contains("study") || !j.contains("series")))
    throw InputError(file, "'" + name +
                               "' names a \"pacs\" without its \"study\" and "
                               "\"series\"");
  if (!pacs && j.contains("study")) throw InputError(file, "'" + name + ".study' needs a \"pacs\"");
  if (!pacs && !j.contains("path")) throw InputError(file, "missing key '" + name + ".path'");
  return e;
}

const FieldTable<RegistrationConfig>& registrationTable() {
  static const FieldTable<RegistrationConfig> t = [] {
    using R = RegistrationConfig;
    FieldTable<R> r;
    r.enumeration("method",
                  "none: by world coordinates (both in LPS mm); rigid or affine: mutual "
                  "information registration when the study is opened; file: the transform file.",
                  &R::method, kRegistrations)
        .add(
            "transform",
            "method file: an ITK transform file (transform.tfm from `mvw register`); relative to "
            "the config file's folder.",
            {"string", "an existing file", "", {}},
            [](const json& v, R& out, const Where& w) {
              const std::string p = detail::readString(v, w);
              if (p.empty()) return;
              out.transform = resolvePath(p, w.file);
            },
            [](const R& in, json& j, const char* k) {
              if (!in.transform.empty()) j[k] = absolutePath(in.transform);
            })
        .number("rotation_search_deg",
                "rigid, affine: a coarse search over rotations up to this many degrees first (0: "
                "none).",
                &R::rotationSearchDeg, 0.0, 180.0);
    return r;
  }();
  return t;
}

const FieldTable<RenderConfig>& renderTable() {
  static const FieldTable<RenderConfig> t = [] {
    FieldTable<RenderConfig> r;
    r.add(
        "views", "The views `mvw render` renders, one image each.",
        {"array of objects", "", "one composite anterior view",
         [](const std::string& path) { return viewTable().describe(path + "[]"); }},
        [](const json& v, RenderConfig& out, const Where& w) {
          if (!v.is_array()) w.bad("must be an array");
          for (std::size_t i = 0; i < v.size(); ++i)
            out.views.push_back(parseViewConfig(v[i], w.file, w.key + "[" + std::to_string(i) + "]",
                                                static_cast<int>(i)));
        },
        [](const RenderConfig& in, json& j, const char* k) {
          json views = json::array();
          for (const ViewConfig& view : in.views) views.push_back(viewConfigJson(view));
          j[k] = views;
        });
    return r;
  }();
  return t;
}

// An array of `n` finite numbers within +-1e6 (LPS mm), or the message `what`.
std::vector<double> readMillimetres(const json& v, const Where& w, std::size_t n,
                                    const std::string& what) {
  if (!v.is_array() || v.size() != n) w.bad(what);
  std::vector<double> out;
  for (const auto& e : v) {
    if (!e.is_number() || !(std::abs(e.get<double>()) <= 1e6)) w.bad(what);
    out.push_back(e.get<double>());
  }
  return out;
}

const FieldTable<Measurements>& measurementsTable() {
  static const FieldTable<Measurements> t = [] {
    using M = Measurements;
    FieldTable<M> m;
    m.add(
         "spheres",
         "Spherical ROIs [L, P, S, radius] in LPS mm; the viewer shows their statistics.",
         {"array of arrays of 4 numbers", "radius > 0", "none", {}},
         [](const json& v, M& out, const Where& w) {
           if (!v.is_array()) w.bad("must be an array of [L, P, S, radius] (LPS mm)");
           out.spheres.clear();
           for (std::size_t i = 0; i < v.size(); ++i) {
             const Where item{w.file, w.key + "[" + std::to_string(i) + "]"};
             const auto a = readMillimetres(
                 v[i], item, 4, "must be [L, P, S, radius] in LPS mm with a radius above 0");
             if (!(a[3] > 0.0))
               item.bad("must be [L, P, S, radius] in LPS mm with a radius above 0");
             out.spheres.push_back({{a[0], a[1], a[2]}, a[3]});
           }
         },
         [](const M& in, json& j, const char* k) {
           if (in.spheres.empty()) return;
           json a = json::array();
           for (const auto& s : in.spheres)
             a.push_back({s.centre[0], s.centre[1], s.centre[2], s.radiusMm});
           j[k] = a;
         })
        .add(
            "rulers", "Distance rulers [L0, P0, S0, L1, P1, S1] in LPS mm.",
            {"array of arrays of 6 numbers", "", "none", {}},
            [](const json& v, M& out, const Where& w) {
              if (!v.is_array()) w.bad("must be an array of [L0, P0, S0, L1, P1, S1] (LPS mm)");
              out.rulers.clear();
              for (std::size_t i = 0; i < v.size(); ++i) {
                const Where item{w.file, w.key + "[" + std::to_string(i) + "]"};
                const auto a =
                    readMillimetres(v[i], item, 6, "must be [L0, P0, S0, L1, P1, S1] in LPS mm");
                out.rulers.push_back({{a[0], a[1], a[2]}, {a[3], a[4], a[5]}});
              }
            },
            [](const M& in, json& j, const char* k) {
              if (in.rulers.empty()) return;
              json a = json::array();
              for (const auto& r : in.rulers)
                a.push_back({r.from[0], r.from[1], r.from[2], r.to[0], r.to[1], r.to[2]});
              j[k] = a;
            });
    return m;
  }();
  return t;
}

// The study object itself: every key delegates to the table of its own object.
const FieldTable<StudyConfig>& studyTable() {
  static const FieldTable<StudyConfig> t = [] {
    using S = StudyConfig;
    FieldTable<S> s;
    s.string("name", "The study's name.", &S::name)
        .add(
            "anatomical", "The anatomical volume (CT or MR): what every view shows.",
            {"object", "", "required",
             [](const std::string& path) { return sourceTable(false).describe(path); }},
            [](const json& v, S& out, const Where& w) {
              out.anatomical = readSource(v, w.file, "anatomical", false).source;
            },
            [](const S& in, json& j, const char* k) {
              j[k] = sourceTable(false).write(SourceEntry{in.anatomical, FunctionalKind::Other});
            })
        .add(
            "functional",
            "A functional volume (PET, SPECT, fMRI, perfusion, dose, labels) placed on the "
            "anatomy.",
            {"object", "", "none",
             [](const std::string& path) { return sourceTable(true).describe(path); }},
            [](const json& v, S& out, const Where& w) {
              const SourceEntry e = readSource(v, w.file, "functional", true);
              out.functional = e.source;
              if (!out.functional->frame) out.functional->frame = defaultFrame(e.kind);
              out.functionalKind = e.kind;
            },
            [](const S& in, json& j, const char* k) {
              if (in.functional)
                j[k] = sourceTable(true).write(SourceEntry{*in.functional, in.functionalKind});
            })
        .add(
            "segmentation",
            "A segmentation (DICOM SEG or a label volume) outlined on MPR views in its segments' "
            "colours.",
            {"object", "", "none",
             [](const std::string& path) { return sourceTable(false).describe(path); }},
            [](const json& v, S& out, const Where& w) {
              out.segmentation = readSource(v, w.file, "segmentation", false).source;
            },
            [](const S& in, json& j, const char* k) {
              if (in.segmentation)
                j[k] =
                    sourceTable(false).write(SourceEntry{*in.segmentation, FunctionalKind::Other});
            })
        .add(
            "registration", "How the functional volume is placed on the anatomy.",
            {"object", "", "method none",
             [](const std::string& path) { return registrationTable().describe(path); }},
            [](const json& v, S& out, const Where& w) {
              registrationTable().read(v, out.registration, Where{w.file, "registration."});
            },
            [](const S& in, json& j, const char* k) {
              if (in.functional) j[k] = registrationTable().write(in.registration);
            })
        .add(
            "render", "What `mvw render` renders.",
            {"object", "", "one composite anterior view",
             [](const std::string& path) { return renderTable().describe(path); }},
            [](const json& v, S& out, const Where& w) {
              renderTable().read(v, out.render, Where{w.file, "render."});
            },
            [](const S& in, json& j, const char* k) { j[k] = renderTable().write(in.render); })
        .add(
            "measurements",
            "What a reader measured in `mvw view`, drawn again when the state is opened.",
            {"object", "", "none",
             [](const std::string& path) { return measurementsTable().describe(path); }},
            [](const json& v, S& out, const Where& w) {
              measurementsTable().read(v, out.measurements, Where{w.file, "measurements."});
            },
            [](const S& in, json& j, const char* k) {
              if (in.measurements != Measurements{})
                j[k] = measurementsTable().write(in.measurements);
            })
        .enumeration("layout",
                     "How `mvw view` arranges its panes: standard (3D + axial, coronal, sagittal "
                     "MPR); pet-ct (anatomical, functional and fused axial MPR in step + the "
                     "functional MIP; pet-ct-coronal, pet-ct-sagittal: that plane).",
                     &S::layout, kLayouts);
    return s;
  }();
  return t;
}

// What no single key can check: keys that need each other.
void checkStudy(const json& j, StudyConfig& config) {
  const fs::path& file = config.file;
  if (!j.contains("anatomical")) throw InputError(file, "missing key 'anatomical'");
  if (j.contains("registration")) {
    if (!config.functional) throw InputError(file, "'registration' needs a 'functional' volume");
    const RegistrationConfig& r = config.registration;
    if (r.method == RegistrationMethod::File) {
      if (r.transform.empty()) throw InputError(file, "missing key 'registration.transform'");
      std::error_code ec;
      if (!fs::exists(r.transform, ec))
        throw InputError(file, "'registration.transform' names " + r.transform.string() +
                                   ", which does not exist");
    }
  }
  if (config.render.views.empty()) {
    ViewConfig defaults;
    defaults.name = "view0";
    defaults.implied = true;
    config.render.views.push_back(defaults);
  }
  for (std::size_t a = 0; a < config.render.views.size(); ++a)
    for (std::size_t b = a + 1; b < config.render.views.size(); ++b)
      if (config.render.views[a].name == config.render.views[b].name)
        throw InputError(file, "two views are named '" + config.render.views[a].name + "'");
}

}  // namespace

json parseJson(std::istream& in, const fs::path& file) {
  // One set of keys per object being read, and the key path to it, for the message.
  std::vector<std::vector<std::string>> keys;
  std::vector<std::string> path;
  const json::parser_callback_t strict = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        keys.emplace_back();
        break;
      case json::parse_event_t::object_end:
        keys.pop_back();
        break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        auto& seen = keys.back();
        if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
          std::string where;
          for (std::size_t d = 0; d + 1 < keys.size() && d < path.size(); ++d)
            where += path[d] + ".";
          throw InputError(file, "the key '" + where + key +
                                     "' appears twice in one object (JSON would keep only the "
                                     "last)");
        }
        seen.push_back(key);
        path.resize(keys.size());
        path.back() = key;
        break;
      }
      default:
        break;
    }
    return true;
  };
  return json::parse(in, strict);
}

StudyConfig loadStudyConfig(const fs::path& file) {
  requireReadable(file);
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open the study config");
  json j;
  try {
    j = parseJson(in, file);
  } catch (const json::exception& e) {  // parse errors, and numbers too large for a double (406)
    std::string name = file.filename().string();
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* volume : {".nii", ".nii.gz", ".hdr", ".mha", ".mhd", ".dcm"})
      if (name.size() >= std::strlen(volume) &&
          name.compare(name.size() - std::strlen(volume), std::string::npos, volume) == 0)
        throw InputError(file,
                         "is a volume, not a study config (JSON): `mvw view` takes a "
                         "volume as --anatomical (and --functional), `mvw render` a "
                         "study config");
    throw InputError(file, std::string("not valid JSON: ") + e.what());
  }
  return studyConfigFromJson(j, file);
}

StudyConfig studyConfigFromJson(const json& j, const fs::path& file) {
  if (!j.is_object()) throw InputError(file, "a study config must be a JSON object");
  StudyConfig config;
  config.file = file;
  studyTable().read(j, config, Where{file, ""});
  checkStudy(j, config);
  return config;
}

void writeStudyConfig(const StudyConfig& config, const fs::path& file) {
  io::writeTextAtomically(file, studyTable().write(config).dump(2) + "\n");
}

FrameChoice defaultFrame(FunctionalKind kind) {
  return kind == FunctionalKind::Labels ? FrameChoice{false, 0} : FrameChoice{true, 0};
}

std::string toString(FunctionalKind kind) { return detail::nameOf(kKinds, kind); }
std::string toString(ViewName view) { return detail::nameOf(kViewNames, view); }
std::string toString(Sampling sampling) { return detail::nameOf(kSamplings, sampling); }
std::string toString(GlyphMethod method) { return detail::nameOf(kGlyphMethods, method); }
std::string toString(GlyphConvexity convexity) { return detail::nameOf(kConvexities, convexity); }
std::string toString(GlyphPlacement placement) { return detail::nameOf(kPlacements, placement); }
std::string toString(RegistrationMethod method) { return detail::nameOf(kRegistrations, method); }
std::optional<ViewName> parseViewName(const std::string& name) {
  return detail::parseName(kViewNames, name);
}
std::optional<Sampling> parseSampling(const std::string& name) {
  return detail::parseName(kSamplings, name);
}
std::string viewNameList() { return detail::namesOf(kViewNames); }

std::pair<double, double> viewNumberRange(const std::string& key) {
  const std::string cue = "depth_cue.";
  const auto range = key.rfind(cue, 0) == 0 ? depthCueTable().range(key.substr(cue.size()))
                                            : viewTable().range(key);
  MVW_CHECK(range.has_value());
  return *range;
}

std::vector<std::string> studyConfigKeyPaths() {
  std::vector<std::string> out;
  auto below = [&](const std::string& key, const std::vector<std::string>& keys) {
    for (const std::string& k : keys) out.push_back(key + "." + k);
  };
  for (const std::string& key : studyTable().keys()) {
    if (key == "anatomical" || key == "segmentation")
      below(key, sourceTable(false).keys());
    else if (key == "functional")
      below(key, sourceTable(true).keys());
    else if (key == "registration")
      below(key, registrationTable().keys());
    else if (key == "render")
      below(key, renderTable().keys());
    else if (key == "measurements")
      below(key, measurementsTable().keys());
    else
      out.push_back(key);  // a value, or an object added later: checked whole
  }
  return out;
}

std::vector<ConfigKeyDoc> studyConfigKeyDocs() { return studyTable().describe(""); }

}  // namespace mvw::config
