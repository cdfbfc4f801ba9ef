#pragma once
// A PET-like functional volume made from a real CT under a known rigid transform, and the
// target registration error against that truth: the test data of issue 3, shared by the
// unit tests and `mvw bench register` so both measure the same thing.
//
// Uptake from HU (soft tissue and brain medium, bone low, air none) plus two hot spheres,
// blurred to a scanner's resolution (6 mm FWHM by default), read onto a grid of 4 mm voxels
// (or any size) under the known transform, with seeded count-like noise (Poisson-like,
// sigma = noise sqrt(value), plus a floor of noise / 10; noise 0.1 by default).
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw::resampling {

struct PetGridOptions {
  // Isotropic voxel size; the field of view stays 256 x 256 x 176 mm (64 x 64 x 44 voxels of
  // 4 mm, 51 x 51 x 35 of 5 mm).
  double voxelMm = 4.0;
  double noise = 0.1;  // sigma of the noise at uptake 1 (soft tissue)
  // Centre the grid on where the head lands in the PET world, for shifts larger than a field
  // of view; otherwise on the CT's centre.
  bool followHead = false;
};

class PetPhantom {
 public:
  // `ct`: a CT in HU (any scalar type, component 0 is used). Only its uptake map (blurred to
  // fwhmMm), centre and TRE lattice are kept.
  explicit PetPhantom(const Volume& ct, double fwhmMm = 6.0);

  // The PET-like volume whose world relates to the CT's by petFromCt (movingFromFixed).
  Volume pet(const glm::dmat4& petFromCt, unsigned seed, const PetGridOptions& grid) const;
  Volume pet(const glm::dmat4& petFromCt, unsigned seed, bool followHead = false) const {
    PetGridOptions grid;
    grid.followHead = followHead;
    return pet(petFromCt, seed, grid);
  }

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

// `mvw phantom pet`: the PET-like volume of `ct` (seeded noise, the default grid) under the
// rigid transform of `rotateDeg` (degrees about x, y, z, ITK Euler order, about the CT's centre)
// and `shiftMm`, described as "mvw PET-like phantom".
Volume petPhantomVolume(const Volume& ct, const glm::dvec3& rotateDeg, const glm::dvec3& shiftMm,
                        unsigned seed);

}  // namespace mvw::resampling
