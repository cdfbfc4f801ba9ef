// libFuzzer: the MetaImage reader (.mha: header and data in one file, raw or zlib-compressed).
#include "FuzzInput.h"
#include "mvw/io/VolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "input.mha");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readVolume(path, options); });
  return 0;
}
