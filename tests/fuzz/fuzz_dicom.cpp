// libFuzzer: the DICOM entry point for one file (`mvw info FILE.dcm`: readAllVolumes, every
// image series the file holds, through vtk-dicom).
#include "FuzzInput.h"
#include "mvw/io/VolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "input.dcm");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readAllVolumes(path, options); });
  return 0;
}
