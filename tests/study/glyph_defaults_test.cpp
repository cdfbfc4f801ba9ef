// Glyph sizes as planned for a view (study ViewPlan): the default diameter and the automatic
// spacing, from the functional voxel and the rendered scale.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "StudyTestUtil.h"
#include "mvw/core/Volume.h"
#include "mvw/render/Framing.h"
#include "mvw/study/ViewPlan.h"

namespace mvw::study {
namespace {

// Defaults: blue-noise glyphs 0.85 of their spacing (provisionally 5 mm until the volumes are
// known); the paper's map keeps its 6 mm.
TEST(GlyphDefaults, DiameterFollowsThePlacementAndSpacing) {
  const auto diameter = [](const nlohmann::json& glyphs) {
    return planViews(studyWith({{"glyphs", glyphs}})).at(0).settings.glyphDiameterMm;
  };
  EXPECT_DOUBLE_EQ(diameter(nlohmann::json::object()), 0.85 * 5.0);
  EXPECT_DOUBLE_EQ(diameter({{"spacing_mm", 8}}), 0.85 * 8.0);
  EXPECT_EQ(diameter({{"placement", "paper"}}), 6.0);
  EXPECT_EQ(diameter({{"spacing_mm", 8}, {"diameter_mm", 3}}), 3.0);
}

// The automatic spacing: the functional voxel, within [what the image shows, 5 mm]; the scale
// wins where a 5 mm glyph would make sub-pixel bumps (a whole-body MIP-sized field of view).
TEST(GlyphDefaults, SpacingFollowsTheFunctionalVoxelAndTheRenderedScale) {
  // The weakest bump's radius is 0.6 * 0.85 / 2 of the spacing; it must be 1.5 px.
  const double perPixel = 1.5 / (0.6 * 0.85 / 2.0);
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(4.0, 0.2, 0.6), 4.0);             // PET voxel
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(2.0, 0.5, 0.6), perPixel * 0.5);  // fine fMRI: scale
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(8.0, 0.2, 0.6), 5.0);             // coarse SPECT: 5 mm
  EXPECT_DOUBLE_EQ(defaultGlyphSpacingMm(4.0, 2.0, 0.6), perPixel * 2.0);  // whole body
  // Through the plan: a 200 mm box (framing radius 100 sqrt 3) at 512 px, zoom 1.
  Volume ct({200, 200, 200}, 1, ScalarType::Int16, glm::dmat4(1.0));
  Volume pet({50, 50, 50}, 1, ScalarType::Float32,
             makeWorldFromIndex({}, {4, 4, 4}, glm::dmat3(1.0)));
  PlannedView v = planViews(studyWith({{"glyphs", nlohmann::json::object()}})).at(0);
  applyGlyphScale(v, ct, pet);
  const double mmPerPixel = 2.0 * render::framingSphere(ct).radius / 512.0;
  const double spacing = defaultGlyphSpacingMm(4.0, mmPerPixel, 0.6);
  EXPECT_DOUBLE_EQ(v.settings.glyphDiameterMm, 0.85 * spacing);
  EXPECT_NEAR(describeView(v.settings, "a", "").glyphSpacingMm.value_or(0), spacing, 1e-9);
  // A given spacing stays.
  PlannedView given = planViews(studyWith({{"glyphs", {{"spacing_mm", 7}}}})).at(0);
  applyGlyphScale(given, ct, pet);
  EXPECT_DOUBLE_EQ(given.settings.glyphDiameterMm, 0.85 * 7);
}

}  // namespace
}  // namespace mvw::study
