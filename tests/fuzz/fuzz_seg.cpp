// libFuzzer: a DICOM Segmentation object (io::readDicomSegmentation, what a study config's
// "segmentation" and the viewer's SEG overlay read), 64 MiB at most as for the other readers.
#include "FuzzInput.h"
#include "mvw/io/DicomSeg.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "seg.dcm");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readDicomSegmentation(path, options); });
  return 0;
}
