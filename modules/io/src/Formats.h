#pragma once
// Per-format entry points behind VolumeReader/VolumeWriter (internal to mvw_io).
#include <filesystem>
#include <vector>

#include "mvw/core/Volume.h"
#include "mvw/io/VolumeReader.h"

namespace mvw::io::detail {

std::vector<Volume> readDicom(const std::filesystem::path& path, const ReadOptions& options,
                              bool allSeries);
Volume readNifti(const std::filesystem::path& path, const ReadOptions& options);
void writeNifti(const Volume& volume, const std::filesystem::path& path);
Volume readMetaImage(const std::filesystem::path& path, const ReadOptions& options);
void writeMetaImage(const Volume& volume, const std::filesystem::path& path);

}  // namespace mvw::io::detail
