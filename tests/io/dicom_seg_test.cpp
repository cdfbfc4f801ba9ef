// The DICOM SEG's recommended display colour (io DicomSeg): CIE L*a*b* as DICOM stores it, to
// sRGB, without files; a SEG whose length field asks for more memory than the process may
// have. The reader on a real SEG is tests/real-data/dicom_seg_test.cpp.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "mvw/core/Error.h"
#include "mvw/io/DicomSeg.h"

#if defined(__SANITIZE_ADDRESS__)
#define MVW_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MVW_TEST_ASAN 1
#endif
#endif

namespace mvw::io {
namespace {

TEST(DicomSeg, CieLabToSrgb) {
  const auto white = io::srgbFromDicomLab(65535, 32896, 32896);
  EXPECT_EQ(white, (std::array<std::uint8_t, 3>{255, 255, 255}));
  // sRGB red is L*a*b* (53.24, 80.09, 67.20) under D65.
  const auto red =
      io::srgbFromDicomLab(static_cast<std::uint16_t>(std::lround(53.24 * 655.35)),
                           static_cast<std::uint16_t>(std::lround((80.09 + 128) * 257)),
                           static_cast<std::uint16_t>(std::lround((67.20 + 128) * 257)));
  EXPECT_GE(red[0], 253);
  EXPECT_LE(red[1], 3);
  EXPECT_LE(red[2], 3);
}

// tests/fuzz/regressions' SEG (the first seg campaign): inside a value of undefined length an
// element claims 0xD7D7D7D7 bytes, which vtk-dicom's parser allocates before it reads. With the
// memory to reserve it the file is refused for its content; with less address space the
// allocation fails, and that must be the file's error too (exit 2), not "internal error: out
// of memory" (exit 1), for every SEG entry point: isDicomSegmentation (`mvw stats --labels`)
// and readDicomSegmentation (a study config's or the viewer's SEG).
TEST(DicomSeg, ALengthBeyondTheMachineIsTheFilesError) {
#ifdef MVW_TEST_ASAN
  GTEST_SKIP() << "ASan reserves terabytes of shadow memory: no RLIMIT_AS to set (the asan "
                  "sweep, tests/fuzz/sweep-regressions, limits its allocator instead)";
#else
  const std::filesystem::path file =
      std::filesystem::path(MVW_SOURCE_DIR) /
      "tests/fuzz/regressions/bad-seg-value-length-vtkdicom-3gib.dcm";
  ASSERT_TRUE(std::filesystem::exists(file));
  const std::filesystem::path err =
      std::filesystem::temp_directory_path() / ("mvw-seg-oom-" + std::to_string(::getpid()));
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::FILE* out = std::fopen(err.c_str(), "w");
    // The address space the child holds now plus 1 GiB: the 3.4 GB cannot be had.
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    const auto size = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGE_SIZE));
    const struct rlimit limit { size + (rlim_t{1} << 30), size + (rlim_t{1} << 30) };
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(5);
    try {
      if (isDicomSegmentation(file)) ::_exit(1);
    } catch (...) {
      std::fputs("isDicomSegmentation threw\n", out);
      std::fflush(out);
      ::_exit(1);
    }
    try {
      (void)readDicomSegmentation(file, ReadOptions{});
      ::_exit(3);
    } catch (const InputError& e) {
      std::fputs(e.what(), out);
      std::fflush(out);
      ::_exit(std::string(e.what()).find("not enough memory to read this file") != std::string::npos
                  ? 0
                  : 2);
    } catch (const std::exception& e) {
      std::fputs(e.what(), out);
      std::fflush(out);
      ::_exit(4);
    }
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  std::string said;
  std::getline(std::ifstream(err), said);
  std::filesystem::remove(err);
  ASSERT_TRUE(WIFEXITED(status)) << said;
  EXPECT_EQ(WEXITSTATUS(status), 0)
      << "1: isDicomSegmentation did not answer false; 2: another refusal; 3: loaded; 4: not an "
         "InputError; 5: no RLIMIT_AS. The child said: "
      << said;
  EXPECT_NE(said.find(file.filename().string()), std::string::npos) << said;
#endif
}

}  // namespace
}  // namespace mvw::io
