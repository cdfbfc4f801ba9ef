#include "mvw/core/Frame.h"

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "mvw/core/Error.h"

namespace mvw {

std::optional<FrameChoice> parseFrameChoice(const std::string& text) {
  if (text == "mean") return FrameChoice{true, 0};
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return FrameChoice{false, std::atoi(text.c_str())};
}

std::string toString(const FrameChoice& choice) {
  return choice.mean ? "mean" : std::to_string(choice.index);
}

Volume selectFrame(const Volume& volume, const FrameChoice& choice) {
  const int frames = volume.components();
  if (!choice.mean && (choice.index < 0 || choice.index >= frames))
    throw InputError(volume.metadata().sourcePath,
                     "frame " + std::to_string(choice.index) + " asked for, but the volume has " +
                         (frames == 1 ? std::string("one frame (0)")
                                      : std::to_string(frames) + " frames (0 .. " +
                                            std::to_string(frames - 1) + ")"));
  if (frames == 1) return volume;
  const ScalarType type = choice.mean ? ScalarType::Float32 : volume.scalarType();
  Volume out(volume.dimensions(), 1, type, volume.worldFromIndex());
  out.metadata() = volume.metadata();
  const std::size_t n = volume.voxelCount();
  if (choice.mean) {
    // Summed in double per voxel: 20 frames of float32 fMRI lose nothing, and the order of
    // the sum is fixed, so the mean is the same on every machine.
    float* dst = out.dataAs<float>();
    dispatchScalar(volume.scalarType(), [&](auto t) {
      using T = decltype(t);
      const T* src = reinterpret_cast<const T*>(volume.data());
      for (std::size_t v = 0; v < n; ++v) {
        double sum = 0.0;
        for (int f = 0; f < frames; ++f) sum += static_cast<double>(src[v * frames + f]);
        dst[v] = static_cast<float>(sum / frames);
      }
      return 0;
    });
    out.metadata().notes.push_back("4D volume of " + std::to_string(frames) +
                                   " frames: the mean over all frames is used (float32)");
  } else {
    const std::size_t bytes = scalarSize(type);
    const std::byte* src = volume.data();
    std::byte* dst = out.data();
    for (std::size_t v = 0; v < n; ++v)
      std::copy_n(src + (v * frames + choice.index) * bytes, bytes, dst + v * bytes);
    out.metadata().notes.push_back("4D volume of " + std::to_string(frames) + " frames: frame " +
                                   std::to_string(choice.index) + " is used");
  }
  return out;
}

}  // namespace mvw
