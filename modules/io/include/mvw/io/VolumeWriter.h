#pragma once
// Writers for NIfTI (.nii, .nii.gz) and MetaImage (.mha, .mhd) that keep the full geometry
// (origin, spacing, direction) so a read gives back the same world mapping. Files are
// written to a temporary name and renamed, so a failed write leaves no partial file.
#include <filesystem>
#include <vector>

#include "mvw/core/Volume.h"

namespace mvw::io {

void writeVolume(const Volume& volume, const std::filesystem::path& path);

// What can be wrong with `output` as a volume file to write, said before any work: a name
// writeVolume does not write (no such extension, or the extension alone: ".nii.gz"), a folder,
// a folder that does not exist or cannot be written, or one of `inputs` (itself or through a
// link: writing would destroy what is being read). Throws InputError naming the output.
void checkVolumeOutput(const std::filesystem::path& output,
                       const std::vector<std::filesystem::path>& inputs = {});

}  // namespace mvw::io
