// A decoder helper that fails on purpose, for isolated_decoder_test: MVW_DECODER names it, and
// MVW_TEST_DECODER_FAULT says how it fails once it has been started and limited as mvw-decoder
// is, and has read its request:
//   crash     SIGSEGV
//   hang      sleeps past the wall-clock limit
//   memory    allocates 256 MiB blocks until one fails (the RLIMIT_AS the caller set), or 64 GiB
//             of them, then decodes as mvw-decoder would: without the limit, it succeeds
//   oversize  answers voxels of 2^20 x 2^20 x 2^20 (never what the headers say)
//   overflow  decodes MVW_TEST_DECODER_OVERFLOW_FILE, a file whose JPEG frame is larger than its
//             Rows and Columns (tests/fuzz/regressions), with GDCM through vtk-dicom, as mvw did
//             before the frame-header checks: a real heap overflow inside the child
// Anything else: decodes as mvw-decoder does.
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <vtkDICOMReader.h>
#include <vtkNew.h>

#include "IsolatedDecoder.h"
#include "mvw/process/Helper.h"
#include "mvw/process/Wire.h"

int main() {
  const int fd = mvw::process::helperSocket();
  if (fd < 0) return 1;
  const char* env = std::getenv("MVW_TEST_DECODER_FAULT");
  const std::string fault = env ? env : "";
  mvw::io::detail::serveDecoder(fd, [&](int socket) {
    if (fault == "crash") {
      std::raise(SIGSEGV);
    } else if (fault == "hang") {
      for (;;) ::pause();
    } else if (fault == "memory") {
      std::vector<std::unique_ptr<char[]>> blocks;
      for (int i = 0; i < 256; ++i) {
        blocks.emplace_back(new char[std::size_t(256) << 20]);
        blocks.back()[0] = 1;
        static volatile char sink = 0;
        sink = static_cast<char>(sink + blocks.back()[0]);  // used: no compiler leaves them out
      }
    } else if (fault == "oversize") {
      mvw::process::Message m;
      m.put(std::uint8_t{1});  // IsolatedDecoder.cpp's Answer::Voxels
      const std::int32_t sent[5] = {1 << 20, 1 << 20, 1 << 20, 1, 4};
      m.put(sent);
      m.put(std::uint64_t{1} << 62);
      m.send(socket);
      ::_exit(0);
    } else if (fault == "overflow") {
      const char* file = std::getenv("MVW_TEST_DECODER_OVERFLOW_FILE");
      vtkNew<vtkDICOMReader> reader;
      reader->SetFileName(file ? file : "");
      reader->Update();
    }
  });
}
