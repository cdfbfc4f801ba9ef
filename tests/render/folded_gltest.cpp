// Folded volumes (VolumeTextures::foldRuns): a volume with more slices than the GL's largest
// 3D texture is stored as runs of slices side by side along x. Every mode must render it as it
// renders the same volume unfolded: the fold is forced here with MVW_MAX_3D_TEXTURE_SIZE on a
// volume whose structures cross the runs' seams, and each view is compared with the unfolded
// render of the same volume in the same context.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include <gtest/gtest.h>

#include "RenderTestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::makeVolume;

// Sets MVW_MAX_3D_TEXTURE_SIZE for one scope.
class TextureLimit {
 public:
  explicit TextureLimit(const char* texels) { setenv("MVW_MAX_3D_TEXTURE_SIZE", texels, 1); }
  ~TextureLimit() { unsetenv("MVW_MAX_3D_TEXTURE_SIZE"); }
  TextureLimit(const TextureLimit&) = delete;
  TextureLimit& operator=(const TextureLimit&) = delete;
};

// 20 x 40 x 150 voxels of 1.5 x 1 x 1 mm: a tube winding along the slices, a ball sitting on
// a run's seam (slices 50 and 100 are shared by two runs with a limit of 64) and a soft
// background, so every mode has edges, surfaces and maxima across the seams.
glm::dmat4 tallGeometry() { return test::axisGrid({-14.25, -19.5, -74.5}, {1.5, 1.0, 1.0}); }
float tallValue(glm::dvec3 p) {
  const glm::dvec2 axis(6.0 * std::sin(p.z / 12.0), 8.0 * std::cos(p.z / 15.0));
  const double tube = 4.0 - glm::length(glm::dvec2(p.x, p.y) - axis);
  const double ball = 7.0 - glm::length(p - glm::dvec3(-3.0, 4.0, -24.5));
  return static_cast<float>(std::max({tube, ball, -6.0 + 0.02 * p.z}));
}

Volume tallFloat() { return makeVolume({20, 40, 150}, tallGeometry(), tallValue); }

Volume tallInt16() {
  return test::makeVolumeOf<std::int16_t>({20, 40, 150}, tallGeometry(), [](glm::dvec3 p) {
    return std::lround(100.0 * tallValue(p));
  });
}

struct Difference {
  int worst = 0;      // largest channel difference, grey levels
  int differing = 0;  // pixels with any difference
  int beyond2 = 0;    // pixels differing by more than 2 grey levels
};
Difference compare(const Image& a, const Image& b) {
  Difference d;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      int worst = 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
      d.worst = std::max(d.worst, worst);
      if (worst > 0) ++d.differing;
      if (worst > 2) ++d.beyond2;
    }
  return d;
}

// Pixels that are not the background: the view must show something for the comparison to mean
// anything.
int shown(const Image& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixel(x, y)[0] > 8 || image.pixel(x, y)[1] > 8 || image.pixel(x, y)[2] > 8) ++n;
  return n;
}

std::vector<RenderSettings> views(double unit) {
  std::vector<RenderSettings> out;
  auto base = [&](RenderMode mode, StandardView view) {
    RenderSettings s =
        test::settingsOf({.mode = mode, .size = {96, 160}, .view = view, .jitterOff = true});
    s.camera.azimuthDeg = view == StandardView::Superior ? 0.0 : 20.0;
    s.camera.elevationDeg = 10.0;
    s.window = {12.0 * unit, 0.0};
    return s;
  };
  for (StandardView view : {StandardView::Anterior, StandardView::Left, StandardView::Superior}) {
    out.push_back(base(RenderMode::Mip, view));
    out.push_back(base(RenderMode::MinIp, view));
    out.push_back(base(RenderMode::Average, view));
    RenderSettings iso = base(RenderMode::Isosurface, view);
    iso.iso = 0.0;
    out.push_back(iso);
    RenderSettings composite = base(RenderMode::Composite, view);
    composite.transfer = TransferFunction{
        "tube",
        false,
        {TfPoint{-1.0 * unit, {1, 0.8f, 0.6f, 0.0f}}, TfPoint{0.0, {1, 0.8f, 0.6f, 0.3f}},
         TfPoint{6.0 * unit, {1, 1, 1, 0.8f}}}};
    out.push_back(composite);
  }
  // MPR: an axial plane through the ball (on a seam) and a coronal one along the whole volume,
  // and a thick slab.
  RenderSettings axial = base(RenderMode::Mpr, StandardView::Superior);
  axial.planeOffsetMm = 24.5;  // the plane moves along the line of sight (toward the feet)
  out.push_back(axial);
  RenderSettings coronal = base(RenderMode::Mpr, StandardView::Anterior);
  out.push_back(coronal);
  coronal.slabMm = 12.0;
  out.push_back(coronal);
  return out;
}

void expectFoldedRendersAsUnfolded(const Volume& volume, double unit, bool linear) {
  test::Renderer unfolded(volume, GradientSource::OnTheFly);
  TextureLimit limit("64");  // 150 slices: 3 runs of 51 (50 + the shared one), 60 texels wide
  VolumeRenderer folded(unfolded.context(), volume);
  EXPECT_EQ(folded.gradientSource(), GradientSource::OnTheFly);
  EXPECT_EQ(folded.valueRange(), unfolded.valueRange());
  for (RenderSettings s : views(unit)) {
    s.linear = linear;
    const std::string what = std::string(toString(s.mode)) + ", " + toString(s.camera.view) +
                             (s.slabMm > 0 ? ", slab" : "") + (linear ? "" : ", nearest");
    const Image a = unfolded.render(s).image;
    const Image b = folded.render(s).image;
    EXPECT_GT(shown(a), 80) << what;
    const Difference d = compare(a, b);
    std::cout << what << ": " << d.differing << " pixels differ, by at most " << d.worst << "\n";
    // The same voxels and weights; the texture coordinates differ in their last bits only,
    // which can flip a ray grazing a surface (a silhouette pixel) between hit and miss.
    EXPECT_LE(d.beyond2, 2) << what;
    EXPECT_LE(d.differing, a.width * a.height / 200) << what;
  }
}

TEST(FoldedVolume, EveryModeRendersAFloatVolumeAsUnfolded) {
  expectFoldedRendersAsUnfolded(tallFloat(), 1.0, true);
}

TEST(FoldedVolume, EveryModeRendersAnInt16VolumeAsUnfolded) {
  expectFoldedRendersAsUnfolded(tallInt16(), 100.0, true);
}

TEST(FoldedVolume, NearestSamplingReadsTheSameVoxels) {
  expectFoldedRendersAsUnfolded(tallInt16(), 100.0, false);
}

// Glyphs read their attribute from a volume on the anatomical grid, folded with it; the shells
// mesh the intensity read back from the folded texture.
TEST(FoldedVolume, GlyphsAndShellsAsUnfolded) {
  const Volume volume = tallFloat();
  const Volume attribute = makeVolume({8, 12, 40}, test::axisGrid({-15, -20, -76}, {4, 4, 4}),
                                      [](glm::dvec3 p) { return p.z < -10.0 ? 0.9f : 0.0f; });
  test::Renderer unfolded(volume, GradientSource::OnTheFly);
  unfolded.setFunctional(attribute, glm::dmat4(1.0));
  TextureLimit limit("64");
  VolumeRenderer folded(unfolded.context(), volume);
  folded.setFunctional(attribute, glm::dmat4(1.0));

  RenderSettings s = test::settingsOf({.mode = RenderMode::Isosurface,
                                       .size = {192, 320},
                                       .view = StandardView::Anterior,
                                       .jitterOff = true});
  s.iso = -2.0;         // the tube 6 mm and the ball 9 mm in radius
  s.camera.zoom = 2.5;  // z from about -31 to 31 mm: both seams, glyphs below -10 mm only
  s.glyphs.on = true;
  s.glyphDiameterMm = 4.0;
  s.functionalWindow = {0.0, 1.0};
  RenderSettings plain = s;
  plain.glyphs.on = false;
  const Image bumps = unfolded.render(s).image;
  const Difference glyphs = compare(bumps, unfolded.render(plain).image);
  EXPECT_GT(glyphs.differing, 100) << "the glyphs must show for the comparison to mean anything";
  const Difference d = compare(bumps, folded.render(s).image);
  std::cout << "glyphs: " << d.differing << " pixels differ, by at most " << d.worst << "\n";
  EXPECT_LE(d.beyond2, 2);
  EXPECT_LE(d.differing, bumps.width * bumps.height / 200);

  for (RenderMode mode : {RenderMode::ShellMip, RenderMode::ShellSum}) {
    RenderSettings shells =
        test::settingsOf({.mode = mode, .size = {96, 160}, .view = StandardView::Left});
    shells.shells = 4;
    const Image a = unfolded.render(shells).image;
    EXPECT_GT(shown(a), 500) << toString(mode);
    const Difference e = compare(a, folded.render(shells).image);
    std::cout << toString(mode) << ": " << e.differing << " pixels differ, by at most " << e.worst
              << "\n";
    EXPECT_EQ(e.worst, 0) << toString(mode) << ": the meshes come from the same values";
  }
}

// What cannot be folded, or asks for what a folded volume does not have, is refused naming the
// volume's file.
TEST(FoldedVolume, RefusesWhatCannotBeFoldedNamingTheFile) {
  auto ctx = test::headlessContext();
  auto refusal = [&](const Volume& v, GradientSource gradient) -> std::string {
    try {
      VolumeRenderer renderer(*ctx, v, gradient);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  TextureLimit limit("64");
  Volume wide = makeVolume({80, 20, 30}, tallGeometry(), tallValue);
  wide.metadata().sourcePath = "wide.nii.gz";
  EXPECT_EQ(refusal(wide, GradientSource::Auto),
            "wide.nii.gz: 80 x 20 x 30 voxels exceed the GL's largest 3D texture (64) across the "
            "slices (only the slice axis can be folded)");
  Volume tallAndBroad = makeVolume({40, 20, 150}, tallGeometry(), tallValue);
  tallAndBroad.metadata().sourcePath = "broad.nii.gz";
  EXPECT_EQ(refusal(tallAndBroad, GradientSource::Auto),
            "broad.nii.gz: 40 x 20 x 150 voxels exceed the GL's largest 3D texture (64): folded "
            "into 3 runs of slices it would be 120 texels wide");
  Volume tall = tallFloat();
  tall.metadata().sourcePath = "tall.nii.gz";
  EXPECT_NE(refusal(tall, GradientSource::Texture)
                .find("tall.nii.gz: 20 x 40 x 150 voxels: more "
                      "slices than the GL's largest 3D texture"),
            std::string::npos);
  EXPECT_EQ(refusal(tall, GradientSource::Auto), "(accepted)");
  TextureLimit bad("lots");
  EXPECT_EQ(refusal(tall, GradientSource::Auto),
            "MVW_MAX_3D_TEXTURE_SIZE: 'lots' is not a whole number of texels from 4 to 1048576");
}

}  // namespace
}  // namespace mvw::render
