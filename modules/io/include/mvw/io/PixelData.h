#pragma once
// The bytes a native (uncompressed) Pixel Data element must hold: the one rule that reading a
// series (io's DicomStacks) and receiving an instance from a PACS (pacs' instance check) apply.
#include <cstdint>
#include <limits>
#include <string>

namespace mvw::io {

// Samples stored per pixel: YBR_FULL_422 and YBR_PARTIAL_422 share the chroma of two pixels, so
// three samples a pixel take the room of two (PS3.3 C.7.6.3.1.2); otherwise SamplesPerPixel.
inline std::uint64_t storedSamplesPerPixel(std::uint64_t samples, const std::string& photometric) {
  return samples == 3 && (photometric == "YBR_FULL_422" || photometric == "YBR_PARTIAL_422")
             ? 2u
             : samples;
}

// ceil(rows x columns x frames x stored samples x BitsAllocated / 8): bit-packed for
// BitsAllocated 1 (a SEG), without the padding to even length. A product beyond 64 bits (a
// header's sizes are not trusted) gives the largest value, which no file holds.
inline std::uint64_t nativePixelDataBytes(std::uint64_t rows, std::uint64_t columns,
                                          std::uint64_t frames, std::uint64_t samples,
                                          std::uint64_t bitsAllocated,
                                          const std::string& photometric) {
  std::uint64_t bits = 1;
  for (std::uint64_t factor :
       {rows, columns, frames, storedSamplesPerPixel(samples, photometric), bitsAllocated})
    if (__builtin_mul_overflow(bits, factor, &bits))
      return std::numeric_limits<std::uint64_t>::max();
  return bits / 8 + (bits % 8 != 0);
}

}  // namespace mvw::io
