// libFuzzer: the DICOM entry point for one file (`mvw info FILE.dcm`: readAllVolumes, every
// image series the file holds, through vtk-dicom), its compressed pixel data decoded in this
// process.
#include "FuzzInput.h"
#include "mvw/io/VolumeReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "input.dcm");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  // The decoders run here, where libFuzzer and the sanitizers see them, not in mvw-decoder.
  options.isolateDecoder = false;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readAllVolumes(path, options); });
  return 0;
}
