#pragma once
// The ray caster's compile-time features (internal to mvw_render), each in one place: one
// entry of raycastFeatures() names the feature's dimension of a program's variant (its values),
// the #defines and shader includes each value brings, the uniforms it alone reads and how they
// are set, the modes it applies to and which setting turns it on. RaycastPrograms builds every
// program from this table, and RaycastPrograms::every() enumerates it: a feature added here is
// compiled by the test that compiles every program without another line. Still one program per
// variant: a feature that is off costs nothing in the ray loop (no runtime branching).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mvw/core/RenderMode.h"
#include "mvw/render/Camera.h"
#include "mvw/render/Framing.h"
#include "mvw/render/RenderSettings.h"
#include "mvw/render/ShaderProgram.h"

namespace mvw::render::detail {

class GlyphTextures;
class TransferTable;

// How glyphs are shaded: one dimension of the variant, so that two shadings at once cannot be
// asked for. Bumps: convex (the default); Dimples: concave; Both: dimples below the middle of
// the attribute's range, bumps above (also chosen labels, each of which carries its own bump or
// dimple); Kinds (issue 40): each glyph's kind read at its foot. Count: how many there are.
enum class GlyphShading { Bumps, Dimples, Both, Kinds, Count };

// The features, in the order of the table. Count: how many there are.
enum class RaycastFeature {
  DepthCue,
  Nearest,
  Tf2d,
  Fusion,
  FusionMean,
  Glyphs,
  GlyphSimple,
  GlyphShading,
  GlyphPaper,
  ImageColormap,
  CutFace,
  Count
};
inline constexpr std::size_t kRaycastFeatureCount = static_cast<std::size_t>(RaycastFeature::Count);
// The most values one feature's dimension has (GlyphShading's four).
inline constexpr int kMaxFeatureValues = 4;

// A program's variant: each feature's value, 0 off (GlyphShading: a GlyphShading).
class RaycastVariants {
 public:
  int operator[](RaycastFeature f) const { return values_[static_cast<std::size_t>(f)]; }
  bool on(RaycastFeature f) const { return (*this)[f] != 0; }
  void set(RaycastFeature f, int value) {
    values_[static_cast<std::size_t>(f)] = static_cast<std::uint8_t>(value);
  }
  GlyphShading glyphShading() const {
    return static_cast<GlyphShading>((*this)[RaycastFeature::GlyphShading]);
  }
  bool operator==(const RaycastVariants&) const = default;

 private:
  std::array<std::uint8_t, kRaycastFeatureCount> values_{};
};

// What the features' uniforms are set from in one frame: its settings, camera and ray step, and
// what the renderer holds for it.
struct FeatureFrame {
  const RenderSettings& settings;
  const Camera& camera;
  double stepMm;
  const FramingSphere& framing;   // the volume's
  const TransferTable& transfer;  // this frame's, updated
  const GlyphTextures& glyphs;    // the map and centres uploaded where glyphs are on
};

// One feature. Its defines and includes count only in a mode it applies to, and only where
// the feature it needs is on too.
struct RaycastFeatureSpec {
  RaycastFeature id;
  const char* name;  // in messages and tests
  int values;        // the values its dimension takes: 2 (off, on), or an enumeration's size
  // Per value, the #define ("NAME VALUE") prepended to the program (nullptr: none; value 0
  // never has one).
  std::array<const char*, kMaxFeatureValues> defines;
  // The shader files (under shaders/) pasted before `mode`'s own file where the feature is on,
  // in this order, each including what it needs (nullptr: none).
  std::vector<const char*> (*includes)(RenderMode mode);
  // The uniforms it alone reads: active in a program with the feature at its last value, in
  // none where it does not count.
  std::vector<const char*> uniforms;
  // Sets `uniforms` for a frame in a program where the feature counts (setFeatureUniforms).
  void (*setUniforms)(const ShaderProgram& program, const FeatureFrame& frame) = nullptr;
  // Uniforms its code reads that VolumeRenderer sets for every program: the samplers (each on
  // its unit, bindTextures) and those that programs without the feature read too (the
  // overlay's, read by isosurface and MPR's runtime fusion; the window).
  std::vector<const char*> sharedUniforms = {};
  bool (*appliesTo)(RenderMode mode);
  RaycastFeature needs;  // the feature that must be on too (Count: none)
  // Its value for a frame's settings; `fusion`: the functional colour is blended in
  // (showsFunctional). The one place the features read RenderSettings.
  int (*valueFor)(const RenderSettings& s, bool fusion);
};

// Every feature, in RaycastFeature's order.
const std::array<RaycastFeatureSpec, kRaycastFeatureCount>& raycastFeatures();

// Whether feature `f` brings its defines and includes into `mode`'s program of variant `v`.
bool featureCounts(const RaycastFeatureSpec& f, RenderMode mode, const RaycastVariants& v);

// Each feature's own uniforms in `program`, `mode`'s of variant `v`, where the feature counts.
void setFeatureUniforms(const ShaderProgram& program, RenderMode mode, const RaycastVariants& v,
                        const FeatureFrame& frame);

}  // namespace mvw::render::detail
