#pragma once
// What a 4D volume (time frames stored as components, see Volume) contributes where one 3D
// volume is needed: one frame, or the mean over all frames. Shared by the study sources
// ("frame" in a study config) and `mvw convert --frame`.
#include <optional>
#include <string>

#include "mvw/core/Volume.h"

namespace mvw {

struct FrameChoice {
  bool mean = false;  // the voxel-wise mean over all frames (float32)
  int index = 0;      // otherwise this frame, counted from 0
};

// "mean" or a frame number (0, 1, ...); nullopt for anything else.
std::optional<FrameChoice> parseFrameChoice(const std::string& text);
std::string toString(const FrameChoice& choice);

// The 3D volume that `choice` takes from `volume`, with a note saying what was taken. A 3D
// volume is returned as it is for frame 0 or "mean". A frame outside 0 .. frames-1 throws
// InputError naming the volume's source file and the frames it has.
Volume selectFrame(const Volume& volume, const FrameChoice& choice);

}  // namespace mvw
