#pragma once
// The reader of the glyph kinds (issue 40 item 4, issue 52): from a glyph render and the same
// render without glyphs alone, the changed pixels are cut into blobs, one glyph each, each
// described by 22 shading statistics in its own frame and classified by its nearest neighbours
// among the patches of another group (another render, or other regions), so that the reader
// never judges a patch by patches of its own group. Shared by the sphere test
// (glyph_kinds_gltest.cpp) and the real-anatomy benchmark (tests/bench/glyph-legibility); no GL.
#include <array>
#include <string>
#include <vector>

#include "mvw/core/Image.h"

namespace mvw::test::reader {

constexpr int kFeatures = 22;  // see describe
using Features = std::array<double, kFeatures>;

// A pixel counts as changed by a glyph where the grey levels differ by this much.
constexpr double kChanged = 4.0;

struct Tile {
  int truth = 0;  // the kind meant where the glyph lies
  int group = 0;  // a tile is classified by the tiles of the other groups only
  Features f{};
};

// The mean of a pixel's red, green and blue.
double grey(const Image& im, int x, int y);
// D = glyph render - plain render, grey levels, row 0 = top (both of one size).
std::vector<double> glyphChange(const Image& glyphs, const Image& plain);

// A connected blob of changed pixels (|D| >= kChanged, grown by one pixel and 8-connected, so
// that it joins across one-pixel seams such as a ridge's crest, where the normal is the
// surface's own).
struct Blob {
  std::vector<int> pixels;  // y * width + x
  bool edge = false;        // touches the image's border
  int middle = 0;           // the pixel nearest its centroid
};
std::vector<Blob> changedBlobs(const std::vector<double>& d, int width, int height);
// The blobs the reader takes as one glyph each: not at the border, not a speck (under a
// quarter of the glyph's disc), not several run together (over 1.6 discs).
bool isGlyphPatch(const Blob& blob, double glyphRadiusPx);

// One glyph's patch described in its own frame, so that the view and the light's strength
// matter little: how much of its disc is changed, how elongated it is, how the change is
// spread over three rings from its centre, how it varies around the centre (2 and 4 fold:
// bars and crosses), its signed balance and the side the light brightens (bumps vs dimples).
Features describe(const std::vector<double>& d, int width, const std::vector<int>& pixels,
                  double glyphRadiusPx);

struct Result {
  std::vector<std::vector<int>> confusion;  // [truth kind][assigned kind]
  int right = 0, total = 0;
};

// k nearest neighbours (k = 7, features scaled by their spread over all tiles) among the tiles
// of the other groups, assigning each tile the kind most of them came from (votes weighed by
// 1 / the kind's share of the tiles).
Result classify(const std::vector<Tile>& tiles, int kinds);

// The confusion matrix, rows the truth, with `title` and the share assigned right.
void print(const Result& r, const std::vector<std::string>& names, const char* title);

}  // namespace mvw::test::reader
