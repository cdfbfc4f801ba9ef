#pragma once
// A rigid or affine map between the worlds of two volumes (both LPS millimetres).
//
// Naming follows the house convention, destination-from-source. The FIXED volume is the
// reference grid (the anatomy), the MOVING one is the volume brought onto it (the functional
// volume), so a Transform is anatomicalFromFunctional:
//   fixedFromMoving: a point given in the moving volume's world -> the same anatomical point
//                    in the fixed volume's world;
//   movingFromFixed: its inverse. This is what resampling needs (for each output voxel of
//                    the fixed grid, where to read the moving volume) and it is what an ITK
//                    transform file stores: ITK transforms map points of the fixed (output)
//                    space to the moving (input) space, in LPS, as SimpleITK, elastix and
//                    3D Slicer's "transform from parent" read them.
#include <filesystem>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace mvw::resampling {

// A rigid map x -> R (x - c) + c + t about a centre c, R from three angles in radians.
// R = Rz * Rx * Ry, the order of ITK's Euler3DTransform (ComputeZYX off), so angles read
// from or compared with ITK tools mean the same thing.
struct RigidParameters {
  glm::dvec3 angles{0.0};       // radians about the x (L), y (P), z (S) axes
  glm::dvec3 translation{0.0};  // mm
};

glm::dmat3 eulerRotation(const glm::dvec3& angles);
// d eulerRotation / d angles[axis].
glm::dmat3 eulerRotationDerivative(const glm::dvec3& angles, int axis);
glm::dmat4 rigidMatrix(const RigidParameters& parameters, const glm::dvec3& centre);
// The inverse of rigidMatrix for a matrix that is rigid (checked by the caller: isRigid).
RigidParameters rigidParameters(const glm::dmat4& rigid, const glm::dvec3& centre);

class Transform {
 public:
  Transform() = default;  // identity
  // `centre` is the centre of rotation in the fixed world (ITK's FixedParameters). It does
  // not change the mapping; it is kept so a round trip through a file is exact.
  explicit Transform(const glm::dmat4& fixedFromMoving, const glm::dvec3& centre = glm::dvec3(0.0));
  static Transform fromMovingFromFixed(const glm::dmat4& movingFromFixed,
                                       const glm::dvec3& centre = glm::dvec3(0.0));

  const glm::dmat4& fixedFromMoving() const { return fixedFromMoving_; }
  const glm::dmat4& movingFromFixed() const { return movingFromFixed_; }
  const glm::dvec3& centre() const { return centre_; }

  glm::dvec3 fixedFromMovingPoint(const glm::dvec3& moving) const;
  glm::dvec3 movingFromFixedPoint(const glm::dvec3& fixed) const;

  // Orthonormal rotation part with determinant +1 (no scaling, shear or reflection).
  bool isRigid(double tolerance = 1e-6) const;

  // ITK text transform (`#Insight Transform File V1.0`, AffineTransform_double_3_3) holding
  // movingFromFixed. Written to a temporary name and renamed: no partial file on failure.
  void writeItk(const std::filesystem::path& path) const;
  // Reads AffineTransform, MatrixOffsetTransformBase, Euler3DTransform,
  // VersorRigid3DTransform and TranslationTransform (double or float, 3-D); anything else,
  // a malformed file or a singular matrix throws mvw::InputError(path, reason).
  static Transform readItk(const std::filesystem::path& path);

 private:
  glm::dmat4 fixedFromMoving_{1.0};
  glm::dmat4 movingFromFixed_{1.0};
  glm::dvec3 centre_{0.0};
};

}  // namespace mvw::resampling
