#pragma once
// How the renderer frames a volume and how finely it samples it unless told otherwise. One
// definition for the renderer, the validator's analytic checks and the tests: they compare
// pixels with hand-computed answers, so they must frame exactly as the renderer does.
#include <utility>

#include <glm/mat4x4.hpp>
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

// The world-aligned box (LPS mm) around a volume's voxel box, whose faces lie half a voxel
// beyond the border voxels' centres, after `worldFrom` maps the volume's world (identity: the
// volume where it is; a registration's anatomicalFromFunctional: where it is placed).
std::pair<glm::dvec3, glm::dvec3> worldBounds(const Volume& volume,
                                              const glm::dmat4& worldFrom = glm::dmat4(1.0));

// The ray-casting step when RenderSettings::stepMm <= 0: half the smallest voxel spacing (mm),
// two samples per voxel along the finest axis.
double defaultStepMm(const Volume& volume);

// Crop boxes are given in patient terms, identical for any storage order: fractions of the
// volume's world-aligned box along L, P, S (0 = its most right / anterior / inferior side,
// 1 = its most left / posterior / superior side), or LPS millimetres. The ray caster clips in
// texture (storage) coordinates; this is the one place that converts. Where the index axes
// run along the patient axes (in any order and sense) the texture box is the crop exactly;
// an oblique (or sheared) volume keeps its whole texture box and is clipped by the crop's box
// in world millimetres instead (worldBox), which the ray caster and MPR also test.
class PatientCrop {
 public:
  explicit PatientCrop(const Volume& volume);
  // The texture-coordinate box (0..1 per index axis) of a box in fractions along L, P, S.
  std::pair<glm::dvec3, glm::dvec3> textureBox(const glm::dvec3& lpsMin,
                                               const glm::dvec3& lpsMax) const;
  // True when every index axis runs along a patient axis (the texture box is exact).
  bool axisAligned() const { return axisAligned_; }
  // The box in LPS mm of fractions along L, P, S.
  std::pair<glm::dvec3, glm::dvec3> worldBox(const glm::dvec3& lpsMin,
                                             const glm::dvec3& lpsMax) const;
  // Fractions along L, P, S (clamped to 0..1) of a box in LPS millimetres.
  std::pair<glm::dvec3, glm::dvec3> fractionsFromMm(const glm::dvec3& minMm,
                                                    const glm::dvec3& maxMm) const;
  // The world-aligned box around the voxel box (faces half a voxel beyond the border
  // voxels' centres), LPS mm.
  const glm::dvec3& boxMin() const { return boxMin_; }
  const glm::dvec3& boxMax() const { return boxMax_; }

 private:
  glm::ivec3 worldAxis_{0, 1, 2};  // the patient axis (0 L, 1 P, 2 S) each index axis follows
  glm::bvec3 reversed_{false};     // index axis runs toward R, A or I
  glm::dvec3 boxMin_{0.0}, boxMax_{0.0};
  bool axisAligned_ = true;
};

}  // namespace mvw::render
