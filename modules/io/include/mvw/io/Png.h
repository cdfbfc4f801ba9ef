#pragma once
// PNG files through libpng: renders, screenshots and
// goldens. Writing is atomic (temporary file + rename); reading never trusts the header's size.
#include <filesystem>

#include "mvw/core/Image.h"

namespace mvw::io {

// Writes an RGBA PNG (8 bits per channel, fast compression) atomically: temp file + rename.
// Throws mvw::Error for an empty image, mvw::InputError naming the file when it cannot write.
void writePng(const Image& image, const std::filesystem::path& path);

// The largest image readPng decodes: 16384 pixels a side and 2^28 pixels in all (1 GiB of RGBA).
inline constexpr int kMaxPngSide = 16384;
inline constexpr long long kMaxPngPixels = 1LL << 28;

// Reads a PNG of any colour type and depth as RGBA8, row 0 on top: grey is copied into R, G and
// B, a missing alpha is 255, 16-bit samples keep their high byte (as OpenCV's imread and most
// viewers do). Throws mvw::InputError naming the file when it is missing, is not a PNG, is
// damaged, or declares a size over the limits above (checked before any pixel is decoded).
Image readPng(const std::filesystem::path& path);

}  // namespace mvw::io
