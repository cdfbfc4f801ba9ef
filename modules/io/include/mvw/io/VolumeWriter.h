#pragma once
// Writers for NIfTI (.nii, .nii.gz) and MetaImage (.mha, .mhd) that keep the full geometry
// (origin, spacing, direction) so a read gives back the same world mapping. Files are
// written to a temporary name and renamed, so a failed write leaves no partial file.
#include <filesystem>

#include "mvw/core/Volume.h"

namespace mvw::io {

void writeVolume(const Volume& volume, const std::filesystem::path& path);

}  // namespace mvw::io
