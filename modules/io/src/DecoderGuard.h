#pragma once
// Third-party decoders (vtk-dicom, GDCM, built with assertions by Debian) abort() on some
// malformed files instead of reporting an error. While a guard is alive, SIGABRT, SIGSEGV,
// SIGBUS and SIGFPE end the process with the usual bad-input message naming the file and
// exit code 2, instead of a core dump. Nothing has been written by then: readers run before
// any output exists. (Internal to mvw_io.)
#include <filesystem>

namespace mvw::io::detail {

class DecoderGuard {
 public:
  // `active` false installs nothing: ReadOptions::isolateDecoder false (the fuzz harness), where
  // an abort or a crash must reach libFuzzer, which keeps the input, instead of exit 2.
  explicit DecoderGuard(const std::filesystem::path& file, bool active = true);
  ~DecoderGuard();
  DecoderGuard(const DecoderGuard&) = delete;
  DecoderGuard& operator=(const DecoderGuard&) = delete;

 private:
  bool active_;
};

}  // namespace mvw::io::detail
