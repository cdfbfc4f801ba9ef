#pragma once
#include <filesystem>

#include "mvw/core/Image.h"

namespace mvw::io {

// Writes an RGBA PNG (OpenCV imgcodecs) atomically: temp file + rename.
void writePng(const Image& image, const std::filesystem::path& path);

}  // namespace mvw::io
