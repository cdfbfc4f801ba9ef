#pragma once
// Everything one render is asked for: mode, size, camera, transfer function, the methods'
// parameters (depth cue, shells, glyphs), the functional overlay and colour maps. Plain data
// with defaults; study::planViews fills it from a study config, the viewer edits it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mvw/core/ColorMap.h"
#include "mvw/core/Crop.h"
#include "mvw/core/DepthCue.h"
#include "mvw/core/GlyphDefaults.h"
#include "mvw/core/GlyphStyle.h"
#include "mvw/core/GradientOpacity.h"
#include "mvw/core/Overlay.h"
#include "mvw/core/RenderMode.h"
#include "mvw/core/WindowLevel.h"
#include "mvw/render/Camera.h"
#include "mvw/render/GlyphMap.h"
#include "mvw/render/TransferFunction.h"

namespace mvw::render {

// A label chosen for glyphs: its number, a bump or a dimple, and its atlas name (if any).
struct LabelGlyph {
  int label = 0;
  GlyphKind kind = GlyphKind::Bumps;
  std::string name;
  bool operator==(const LabelGlyph&) const = default;
};

// Whether glyphs take the kinds' shading (MVW_GLYPH_KINDS, issue 40): a chosen label's kind
// other than bumps and dimples, or kinds for the classes. Bumps and dimples alone keep the
// "both" shading they always had, pixel for pixel.
struct RenderSettings;
bool usesGlyphKinds(const RenderSettings& s);

// The modes and glyph kinds are the study config's vocabulary too (mvw/core/RenderMode.h).
using mvw::CutFace;
using mvw::GlyphConvexity;
using mvw::GlyphKind;
using mvw::GlyphMethod;
using mvw::GlyphStyle;
using mvw::parseRenderMode;
using mvw::RenderMode;
using mvw::toString;

struct RenderSettings {
  RenderMode mode = RenderMode::Composite;
  glm::ivec2 size{512, 512};
  CameraSettings camera;
  TransferFunction transfer = transferPreset("ct-bone");
  // 2D transfer function (mvw/core/GradientOpacity.h); off: 1D only.
  GradientOpacity gradientOpacity;
  // Projections, MPR and the anatomy on a cut face (cutFace): width and centre; unset, the
  // full value range (mvw/core/WindowLevel.h).
  WindowLevel window;
  double iso = 300.0;
  // MIP and the shell modes with depth cueing (mvw/core/DepthCue.h).
  DepthCue depthCue;
  // Shell modes: n shells at emissions i/n of the window; shells can be disabled one by one.
  int shells = 8;
  std::vector<bool> shellEnabled;  // empty: all
  double stepMm = 0.0;             // <= 0: half the smallest voxel spacing
  bool shading = true;
  bool linear = true;  // trilinear (true) or nearest-neighbour sampling
  bool jitter = true;
  std::uint32_t seed = 1;
  glm::vec3 background{0.0f};
  glm::vec4 isoColor{0.92f, 0.86f, 0.76f, 1.0f};
  glm::vec4 light{0.25f, 0.7f, 0.25f, 24.0f};  // ambient, diffuse, specular, shininess
  // Where the light comes from, in screen terms: (0, 0) is a headlight; (-1, 1) from the
  // upper left at 45 degrees off the line of sight.
  glm::dvec2 lightOffset{0.0};
  // Crop box in patient terms (mvw/core/Crop.h; PatientCrop, Framing.h, turns it into boxes).
  Crop crop;
  // Composite and isosurface with a crop: the opaque cut face shows the anatomy's grey values
  // under window / level, glyphs and fusion on it (MVW_CUT_FACE), or the isosurface colour and
  // the transfer function (plain). Plain here, so that settings made by hand keep the look
  // they had; study::prepareViews turns it on as the config's cut_face says (anatomy by
  // default) and gives the window.
  CutFace cutFace = CutFace::Plain;
  // MPR: the plane faces the camera through the volume centre, moved along the line of
  // sight; a slab > 0 mm is a thick-slab MIP. (Always orthographic.)
  double planeOffsetMm = 0.0;
  double slabMm = 0.0;
  // Volumetric normal glyphs (Seipel 2007) in composite and isosurface modes: the functional
  // attribute (mapped to 0..1 by functionalWindow) perturbs the shading normal with glyphs
  // from a periodic normal map. Needs a functional volume. How they are drawn
  // (mvw/core/GlyphStyle.h); where they sit, the map and its diameter on the patient below.
  GlyphStyle glyphs;
  double glyphDiameterMm = kPaperGlyphDiameterMm;  // the default map is the paper's
  GlyphMapSettings glyphMap;  // size, count, diameter in map voxels, seed, placement
  // Composite DVR with glyph kinds (issue 52, a prototype): > 0 draws only the glyphs whose
  // centre lies within this many mm beyond the ray's first glyph sample, one layer of the 3D
  // lattice instead of glyphs from several depths run together on the screen; whole or
  // nothing per glyph, as the test is on its centre. 0: every depth (today's images).
  // Renderer only (no config key), so not in GlyphStyle.
  double glyphLayerMm = 0.0;
  // Functional values mapped to 0..1 (colour map, glyph beta); unset: the value range.
  ValueWindow functionalWindow;
  // Nominal attribute (labels), chosen by the reader (issue 15 item 4): when not empty only
  // these labels get glyphs, each a full-size bump or dimple (the "both" shading of
  // glyphs.glsl); other labels and 0 get none.
  std::vector<LabelGlyph> glyphLabels;
  // Nominal attribute (labels): K > 0 maps label L > 0 to glyph size (L mod K + 1) / K.
  int functionalClasses = 0;
  // Functional colour overlay and fusion, when the renderer holds a functional volume
  // (mvw/core/Overlay.h).
  Overlay overlay;
  // MPR: outline the segments of a segmentation set with setSegmentation, in their colours.
  bool segmentationOutlines = true;
  // Colour maps (mvw/core/ColorMap.h; io::standardColorTable fills the DICOM palettes): the
  // image of MIP, MinIP, average and MPR views (none: grey), looked up by the grey byte, the
  // background shown through it as the grey it is; and the functional overlay and fusion
  // (none: hot metal). Other modes ignore imageColors.
  std::optional<ColorTable> imageColors;
  std::optional<ColorTable> overlayColors;
};

// Whether the crop cuts the volume: a box in mm, or fractions other than 0 .. 1.
bool cropsVolume(const RenderSettings& settings);
// Whether a render of `settings` shows the anatomy on a cut face (MVW_CUT_FACE): composite or
// isosurface, cropped, with CutFace::Anatomy. Renders without a crop keep their program.
bool showsAnatomyOnCutFace(const RenderSettings& settings);

// Whether `settings` colours its image (a colour map on a mode that takes one).
using mvw::takesImageColors;
bool showsImageColors(const RenderSettings& settings);

// Whether a render of `settings` shows the functional volume in colour, given whether the
// renderer holds one: MPR its overlay, a mode that takes fusion when asked. What captions and
// colour bars go by, so that they name nothing the image does not show.
using mvw::FusionProjection;
using mvw::takesFusion;
bool showsFusion(const RenderSettings& settings, bool hasFunctional);
bool showsFunctional(const RenderSettings& settings, bool hasFunctional);

}  // namespace mvw::render
