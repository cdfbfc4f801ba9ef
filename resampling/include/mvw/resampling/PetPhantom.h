#pragma once
// A PET-like functional volume made from a real CT under a known rigid transform, and the
// target registration error against that truth: the test data of issue 3, shared by the
// unit tests and `mvw bench register` so both measure the same thing.
//
// Uptake from HU (soft tissue and brain medium, bone low, air none) plus two hot spheres,
// blurred to 6 mm FWHM, read onto a 4 mm grid under the known transform, with seeded
// count-like noise (Poisson-like, sigma = 0.1 sqrt(value), plus a small floor).
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw::resampling {

class PetPhantom {
 public:
  // `ct`: a CT in HU (any scalar type, component 0 is used). Only its uptake map, centre and
  // TRE lattice are kept.
  explicit PetPhantom(const Volume& ct);

  // The PET-like volume whose world relates to the CT's by petFromCt (movingFromFixed).
  // The 64 x 64 x 44 grid of 4 mm voxels is centred on the CT's centre, or (followHead) on
  // where the head lands in the PET world, for shifts larger than a field of view.
  Volume pet(const glm::dmat4& petFromCt, unsigned seed, bool followHead = false) const;

  // Mean distance (mm) between the estimated and the true PET position of the lattice
  // points: every 10th voxel in i and j and every 7th in k of the CT, where it is above
  // -300 HU (inside the head).
  double meanTre(const glm::dmat4& estimatedPetFromCt, const glm::dmat4& truePetFromCt) const;

  const glm::dvec3& centre() const { return centre_; }  // of the CT's voxel box, world mm
  const Volume& uptake() const { return uptake_; }
  const std::vector<glm::dvec3>& lattice() const { return lattice_; }

 private:
  Volume uptake_;
  glm::dvec3 centre_{0.0};
  std::vector<glm::dvec3> lattice_;
};

}  // namespace mvw::resampling
