#pragma once
// How the renderer frames a volume and how finely it samples it unless told otherwise. One
// definition for the renderer, the validator's analytic checks and the tests: they compare
// pixels with hand-computed answers, so they must frame exactly as the renderer does.
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw::render {

// The sphere a camera shows whole at zoom 1 (makeCamera): centred on the voxel box, whose
// faces lie half a voxel beyond the border voxels' centres, with half its diagonal as radius
// (LPS mm). The ray caster also measures depth cueing and its step budget against it.
struct FramingSphere {
  glm::dvec3 centre{0.0};
  double radius = 0.0;
};
FramingSphere framingSphere(const Volume& volume);

// The ray-casting step when RenderSettings::stepMm <= 0: half the smallest voxel spacing (mm),
// two samples per voxel along the finest axis.
double defaultStepMm(const Volume& volume);

}  // namespace mvw::render
