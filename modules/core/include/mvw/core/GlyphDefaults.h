#pragma once
// The one default of each glyph parameter (issue 15: "one default per parameter, defined in one
// place"): the study config (config::ViewConfig) and the renderer (render::RenderSettings) both
// start from these. Glyphs are Seipel 2007's volumetric normal glyphs; where a default goes
// beyond the paper it says so.
namespace mvw {

// Blue-noise placement: the glyph centres' spacing (mm) when neither the view nor the rendered
// scale asks for another (see study::defaultGlyphSpacingMm), and the glyph diameter as a
// fraction of it (dense packing that still leaves the glyphs apart).
inline constexpr double kGlyphSpacingMm = 5.0;
inline constexpr double kBlueNoiseDiameterFraction = 0.85;
// The weakest bump's apparent radius on the image (pixels) that the default spacing keeps.
inline constexpr double kGlyphMinBumpPixels = 1.5;
// Glyph kinds (issue 40): a shape is read, not only a bump seen, so the default spacing keeps
// a full-size glyph this many pixels in radius (measured: GlyphKinds in
// tests/render/glyph_kinds_gltest.cpp; docs/user-guide/glyphs.md#glyph-kinds).
inline constexpr double kGlyphKindRadiusPixels = 12.0;
// The paper's own map (16 random glyphs of 32 voxels in 128^3) on the patient.
inline constexpr double kPaperGlyphDiameterMm = 6.0;
// Beyond the paper: the apparent bump radius just above the attribute window's low end, in
// glyph radii (it grows linearly to 1 at the high end), so the weakest finding is a bump a
// reader sees.
inline constexpr double kGlyphMinSize = 0.6;
// Beyond the paper, composite DVR only: the least opacity per millimetre of ray a bump gives
// the samples it tilts. In translucent tissue (brain under a bone preset) a perturbed normal
// alone changes a pixel by a few grey levels; with this floor a bump is shaded like a small
// surface and keeps its light-to-shadow contrast. 0 restores the paper's shading.
inline constexpr double kGlyphDvrOpacityPerMm = 0.25;

// The largest label number that can be chosen for glyphs: chosen labels live in a table over
// label numbers (a 1D texture; GL_MAX_TEXTURE_SIZE is at least 16384 in GL 4.x).
inline constexpr int kMaxGlyphLabel = 16383;

}  // namespace mvw
