#pragma once
// Puts every acquired slice of a DICOM stack where its ImagePositionPatient says.
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "mvw/core/Volume.h"

namespace mvw::io::detail {

// `stack` is the decoded series: slice k of it was acquired with its first pixel at
// positions[k] (LPS mm); its worldFromIndex gives the row and column directions and pixel
// spacings. Sets metadata().sliceSpacing from the positions. When the slices are evenly
// spaced and lie on the normal through the first one, returns the stack with the matrix
// that puts slice 0 at positions[0] (today's volume, bit for bit); otherwise resamples onto a
// regular orthogonal grid (see SliceGeometry.cpp) and adds notes saying what happened.
// `spacing` > 0 chooses the grid's slice distance in mm (0: automatic). The output is held
// to `maxBytes` (InputError naming `file`).
Volume placeSlices(Volume stack, const std::vector<glm::dvec3>& positions, double spacing,
                   std::size_t maxBytes, const std::filesystem::path& file);

}  // namespace mvw::io::detail
