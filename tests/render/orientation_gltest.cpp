// Left and right must be right: markers toward L, P and S land where the orientation labels
// say, whatever order the voxels are stored in.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "../support/TestUtil.h"
#include "RenderTestUtil.h"
#include "mvw/core/Orientation.h"
#include "mvw/io/Png.h"
#include "mvw/io/VolumeReader.h"
#include "mvw/io/VolumeWriter.h"
#include "mvw/render/Framing.h"
#include "mvw/render/VolumeRenderer.h"

namespace mvw::render {
namespace {

using test::Centroid;
using test::centroidOf;
using test::makeVolume;

// A dark cube with bright markers 15 mm toward the patient's left, posterior and superior.
float markers(glm::dvec3 p) {
  auto near = [&](glm::dvec3 c) { return glm::length(p - c) < 4.0; };
  if (near({15, 0, 0})) return 1000.0f;  // L
  if (near({0, 15, 0})) return 600.0f;   // P
  if (near({0, 0, 15})) return 300.0f;   // S
  return 0.0f;
}

TEST(Raycast, MarkersAppearWhereTheOrientationLabelsSayForAnyStorageOrder) {
  // The same world content stored in LPS order and in RAS order (flipped i and j).
  const glm::ivec3 d(41, 41, 41);
  const Volume lps = makeVolume(d, test::axisGrid({-20, -20, -20}, {1, 1, 1}), markers);
  const Volume ras =
      makeVolume(d,
                 makeWorldFromIndex(
                     {20, 20, -20}, {1, 1, 1},
                     glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1))),
                 markers);
  auto ctx = test::headlessContext();
  for (const Volume* v : {&lps, &ras}) {
    VolumeRenderer renderer(*ctx, *v);
    RenderSettings s = test::settingsOf({
        .mode = RenderMode::Mip,
        .size = {101, 101},
        .view = StandardView::Anterior,  // screen right = patient left, up = superior
        .jitterOff = true,
    });
    s.window = {1000, 500};
    s.linear = false;  // nearest: marker edges keep their exact grey (255, 153, 76)
    RenderedFrame f = renderer.render(s);
    const Centroid left = centroidOf(f.image, 250, 255), sup = centroidOf(f.image, 70, 82);
    ASSERT_GT(left.n, 10);
    ASSERT_GT(sup.n, 10);
    EXPECT_GT(left.x, 65);  // L marker on the right half
    EXPECT_NEAR(left.y, 50, 3);
    EXPECT_LT(sup.y, 35);  // S marker at the top
    EXPECT_NEAR(sup.x, 50, 3);
    s.camera.view = StandardView::Left;  // screen right = posterior
    f = renderer.render(s);
    const Centroid post = centroidOf(f.image, 148, 158);
    ASSERT_GT(post.n, 10);
    EXPECT_GT(post.x, 65);
    EXPECT_NEAR(post.y, 50, 3);
  }
}

// Crops in patient terms (issue 14 item 3): the Cranium CT and the same CT stored two other
// ways (slice axis reversed in memory; columns and slices reversed, written and read back
// through NIfTI) under one crop box, "keep the inferior 55 %", give the same pictures. Under
// the old storage-order semantics the reversed copies kept the superior part instead.
// `v` with the index axes marked in `flip` reversed and the geometry changed to match, so
// every voxel keeps its world position.
Volume storedReversed(const Volume& v, glm::bvec3 flip) {
  const glm::ivec3 d = v.dimensions();
  glm::dmat4 m = v.worldFromIndex();
  for (int a = 0; a < 3; ++a)
    if (flip[a]) {
      m[3] += m[a] * double(d[a] - 1);
      m[a] = -m[a];
    }
  Volume out(d, 1, v.scalarType(), m);
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i)
        out.setValue(flip.x ? d.x - 1 - i : i, flip.y ? d.y - 1 - j : j, flip.z ? d.z - 1 - k : k,
                     0, v.value(i, j, k));
  return out;
}

struct Difference {
  double psnr = 0.0;
  int worst = 0;
};
Difference compare(const Image& a, const Image& b) {
  double se = 0.0;
  int worst = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int e = std::abs(int(a.pixel(x, y)[c]) - int(b.pixel(x, y)[c]));
        se += double(e) * e;
        worst = std::max(worst, e);
      }
  const double mse = se / (3.0 * a.width * a.height);
  return {mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0, worst};
}

TEST(Raycast, CropBoxIsInPatientTermsForAnyStorageOrder) {
  const Volume ct = test::sampleCranium();
  ASSERT_EQ(orientationCode(ct.direction()), "LPS");
  const Volume slicesReversed = storedReversed(ct, {false, false, true});
  const auto dir = test::scratchDir();
  io::writeVolume(storedReversed(ct, {true, false, true}), dir / "ct-ri.nii.gz");
  const Volume written = io::readVolume(dir / "ct-ri.nii.gz");
  ASSERT_EQ(orientationCode(written.direction()), "RPI");
  ASSERT_EQ(orientationCode(slicesReversed.direction()), "LPI");

  auto ctx = test::headlessContext();
  struct StorageCase {
    RenderMode mode;
    StandardView view;
  };
  for (const StorageCase c : {StorageCase{RenderMode::Composite, StandardView::Superior},
                              StorageCase{RenderMode::Mip, StandardView::Anterior}}) {
    RenderSettings s = test::settingsOf({.mode = c.mode, .size = {121, 121}, .view = c.view});
    s.transfer = transferPreset("ct-bone");
    s.window = {2000, 900};
    s.crop.max = {1.0, 1.0, 0.55};  // the inferior 55 % of the head
    std::vector<Image> images;
    for (const Volume* v : {&ct, &slicesReversed, &written})
      images.push_back(VolumeRenderer(*ctx, *v).render(s).image);
    // The crop in the storage order of the reversed copy: what the old semantics showed.
    RenderSettings old = s;
    old.crop.min = {0.0, 0.0, 0.45};
    old.crop.max = {1.0, 1.0, 1.0};
    const Image superiorPart = VolumeRenderer(*ctx, ct).render(old).image;
    // The same box in LPS millimetres ("crop_mm"), on the copy written through NIfTI.
    RenderSettings mm = s;
    const PatientCrop box(written);
    mm.crop.minMm = box.boxMin();
    mm.crop.maxMm = box.boxMax() - glm::dvec3(0, 0, 0.45 * (box.boxMax().z - box.boxMin().z));
    mm.crop.max = glm::dvec3(1.0);  // the millimetres win
    images.push_back(VolumeRenderer(*ctx, written).render(mm).image);
    for (std::size_t i = 1; i < images.size(); ++i) {
      const Difference d = compare(images[0], images[i]);
      std::cout << "[ crop ] mode " << int(c.mode) << " copy " << i << ": PSNR " << d.psnr
                << " dB, worst " << d.worst << "/255\n";
      EXPECT_GE(d.psnr, 55.0) << "copy " << i;  // llvmpipe: bit-identical (worst 0)
      EXPECT_LE(d.worst, 4) << "copy " << i;
    }
    const std::string stem = (dir / ("crop-" + std::to_string(int(c.mode)))).string();
    io::writePng(images[0], stem + "-stored-lps.png");
    io::writePng(images[2], stem + "-stored-rpi.png");
    io::writePng(superiorPart, stem + "-old-semantics.png");
    const Difference o = compare(images[0], superiorPart);
    std::cout << "[ crop ] mode " << int(c.mode) << " old semantics: PSNR " << o.psnr << " dB\n";
    EXPECT_LT(o.psnr, 25.0);
  }
}

// An oblique volume (tilted 30 degrees about L, as a gantry tilt tilts it) cropped at half its
// superior extent: the cut is the world plane S = const, not the tilted slice plane. Seen from
// the front, every column of the uniform block's MIP ends at the same row, the cut's row.
TEST(Raycast, ObliqueVolumeIsCroppedAlongThePatientAxes) {
  const double a = glm::radians(30.0);
  const glm::dmat3 tilt(glm::dvec3(1, 0, 0), glm::dvec3(0, std::cos(a), std::sin(a)),
                        glm::dvec3(0, -std::sin(a), std::cos(a)));
  const glm::ivec3 d(40, 40, 40);
  const Volume v = makeVolume(d, makeWorldFromIndex(tilt * glm::dvec3(-19.5), {1, 1, 1}, tilt),
                              [](glm::dvec3) { return 1000.0f; });
  const PatientCrop crop(v);
  ASSERT_FALSE(crop.axisAligned());
  test::Renderer renderer(v);
  RenderSettings s = test::settingsOf({.mode = RenderMode::Mip,
                                       .size = {121, 121},
                                       .view = StandardView::Anterior,
                                       .jitterOff = true});
  s.window = {1000, 500};
  s.crop.max = {1.0, 1.0, 0.5};
  const RenderedFrame f = renderer.render(s);
  // The cut's row: the world point on the cut plane at the centre, through the camera.
  const double zCut = 0.5 * (crop.boxMin().z + crop.boxMax().z);
  const glm::dvec4 clip = f.camera.clipFromWorld * glm::dvec4(0.0, 0.0, zCut, 1.0);
  const double rowCut = (1.0 - (clip.y / clip.w * 0.5 + 0.5)) * s.size.y;  // rows run down
  int columns = 0;
  for (int x = 0; x < s.size.x; ++x) {
    int top = -1;
    for (int y = 0; y < s.size.y && top < 0; ++y)
      if (f.image.pixel(x, y)[0] > 128) top = y;
    if (top < 0) continue;
    ++columns;
    EXPECT_NEAR(top, rowCut, 1.0) << "column " << x;
  }
  EXPECT_GT(columns, 30);
}

}  // namespace
}  // namespace mvw::render
