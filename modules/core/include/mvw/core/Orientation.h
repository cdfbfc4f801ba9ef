#pragma once
// Orientation codes in the "points toward" convention used by DICOM viewers and nibabel:
// the letter for an index axis names the patient side that axis increases toward. With
// LPS world coordinates an identity direction matrix is "LPS"; a NIfTI file stored in RAS
// order (x toward Right) is "RAS".
#include <string>

#include <glm/mat3x3.hpp>

namespace mvw {

std::string orientationCode(const glm::dmat3& direction);

// True when some index axis is further than `toleranceDegrees` from every world axis.
bool isOblique(const glm::dmat3& direction, double toleranceDegrees = 1.0);

}  // namespace mvw
