#pragma once
// A registration as a DICOM Spatial Registration object: the moving (functional) volume's
// frame of reference mapped onto the fixed (anatomical) one by a 4x4 matrix in the DICOM
// patient frame (LPS mm), referencing both series. In the fixed volume's study.
#include <filesystem>

#include <glm/mat4x4.hpp>

#include "mvw/dicomout/DicomIdentity.h"
#include "mvw/dicomout/SecondaryCapture.h"

namespace mvw::dicomout {

// fixedFromMoving maps a point of the moving volume's world to the fixed one's (what DICOM's
// Frame of Reference Transformation Matrix holds: registered RCS from source RCS). affine:
// matrix type AFFINE, else RIGID. comment: the Frame of Reference Transformation Comment
// (at most 64 characters are kept).
void writeSpatialRegistration(const std::filesystem::path& file, const DicomIdentity& fixed,
                              const DicomIdentity& moving, const glm::dmat4& fixedFromMoving,
                              bool affine, const SeriesInfo& series, const std::string& comment);

}  // namespace mvw::dicomout
