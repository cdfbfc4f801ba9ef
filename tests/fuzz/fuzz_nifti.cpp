// libFuzzer: the NIfTI reader (NIfTI-1/2, plain or gzip-compressed single files).
#include "FuzzInput.h"
#include "mvw/io/VolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  const auto path = mvw::fuzz::writeInput(data, size, gz ? "input.nii.gz" : "input.nii");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readVolume(path, options); });
  return 0;
}
