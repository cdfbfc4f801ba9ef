#pragma once
// Resampling a moving volume onto a fixed (reference) grid under a Transform.
// The output has exactly the grid's dimensions and worldFromIndex, the moving volume's
// scalar type, unit and modality; output voxels whose centre maps outside the moving volume
// (further than half a voxel beyond its edge voxels) get the background value.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"
#include "mvw/resampling/Transform.h"

namespace mvw::resampling {

enum class Interpolation {
  Automatic,  // nearest for label maps (looksLikeLabelMap), linear otherwise
  Nearest,
  Linear,
  Cubic,
};

// The sampling lattice of an output volume: what resample needs of the fixed volume.
struct Grid {
  glm::ivec3 dimensions{0};
  glm::dmat4 worldFromIndex{1.0};
};
Grid gridOf(const Volume& volume);

struct ResampleOptions {
  Interpolation interpolation = Interpolation::Automatic;
  double background = 0.0;
  bool allComponents = true;  // false: component 0 only (the first frame of a 4-D series)
};

// An integer volume with few distinct values: at most 64 for 8-bit types (a grey-level
// 8-bit image uses most of its 256 levels, an atlas rarely more than a few dozen), at most
// 256 for wider integer types (CT, PET or MR stored as integers have thousands). Linear
// interpolation would invent labels that do not exist between two neighbouring regions.
bool looksLikeLabelMap(const Volume& volume);

// The interpolation `options` asks for, with Automatic decided for `moving`.
Interpolation chosenInterpolation(const Volume& moving, const ResampleOptions& options);

Volume resample(const Volume& moving, const Grid& fixedGrid, const Transform& fixedFromMoving,
                const ResampleOptions& options = {});

}  // namespace mvw::resampling
