// libFuzzer: a DICOM Segmentation object (io::readDicomSegmentation, what a study config's
// "segmentation" and the viewer's SEG overlay read), 64 MiB at most as for the other readers.
#include "FuzzInput.h"
#include "mvw/io/DicomSeg.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mvw::fuzz::writeInput(data, size, "seg.dcm");
  mvw::io::ReadOptions options;
  options.maxBytes = mvw::fuzz::kMaxBytes;
  // The decoder guard stands aside, as in fuzz_dicom: an abort in vtk-dicom's parser reaches
  // libFuzzer, which keeps the input, instead of the guard's _exit(2), which ended the campaign
  // with no input kept.
  options.isolateDecoder = false;
  mvw::fuzz::expectInputErrorOnly([&] { (void)mvw::io::readDicomSegmentation(path, options); });
  return 0;
}
