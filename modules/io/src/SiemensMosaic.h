#pragma once
// Siemens MOSAIC images: the slices of one acquisition stored as tiles of one 2D image.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "mvw/core/Volume.h"

namespace mvw::io::detail {

// `mosaic` is the decoded single image (nx x ny x 1) with the geometry of its header (row and
// column directions, pixel spacing, ImagePositionPatient at voxel 0). `csa` is the CSA Image
// Header Info (0029,xx10). `spacingBetweenSlices` (mm, <= 0 when absent) places the tiles
// along the slice normal. Returns the tiles as slices with corrected positions; when the CSA
// header is missing or malformed, returns the image unchanged with a note saying why.
Volume unpackMosaic(Volume mosaic, const std::uint8_t* csa, std::size_t csaSize,
                    double spacingBetweenSlices, double sliceThickness);

}  // namespace mvw::io::detail
