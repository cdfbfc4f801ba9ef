// libFuzzer: the PNG reader (io::readPng: goldens and images handed to `mvw validate`).
#include "FuzzInput.h"
#include "mvw/io/Png.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "input.png");
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readPng(path); });
  return 0;
}
