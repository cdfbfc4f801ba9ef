// Compressed DICOM pixel data decoded by a child process (modules/io/src/IsolatedDecoder.h):
// the child's voxels are this process's, byte for byte; native pixel data needs no child; and a
// real child that crashes, hangs, blows its memory limit, lies about its size or writes past a
// heap buffer inside GDCM is the file's error (InputError), after which this process reads on.
// The failing children are tests/io/decoder_faults_main.cpp, named by MVW_DECODER.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>

#include "TestUtil.h"
#include "mvw/core/Error.h"
#include "mvw/io/VolumeReader.h"

namespace {

namespace fs = std::filesystem;
using mvw::InputError;
using mvw::Volume;
using mvw::io::ReadOptions;

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

Volume readInThisProcess(const fs::path& file) {
  ReadOptions options;
  options.isolateDecoder = false;
  return mvw::io::readVolume(file, options);
}

void expectSame(const Volume& a, const Volume& b, const fs::path& file) {
  SCOPED_TRACE(file.string());
  ASSERT_EQ(a.dimensions(), b.dimensions());
  ASSERT_EQ(a.components(), b.components());
  ASSERT_EQ(a.scalarType(), b.scalarType());
  ASSERT_EQ(a.byteSize(), b.byteSize());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.byteSize()));
  EXPECT_EQ(a.worldFromIndex(), b.worldFromIndex());
  EXPECT_EQ(a.metadata().notes, b.metadata().notes);
}

// The message of the InputError reading `file` throws; "" (and a failure) when it reads.
std::string errorReading(const fs::path& file) {
  try {
    (void)mvw::io::readVolume(file);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " read without an error";
  return "";
}

const fs::path kJpeg = "pydicom/test_files/SC_rgb_jpeg_dcmtk.dcm";

TEST(IsolatedDecoder, CompressedFilesDecodeInTheChildAsInThisProcess) {
  for (const char* name :
       {"SC_rgb_jpeg_dcmtk.dcm", "JPEG-lossy.dcm", "MR_small_jpeg_ls_lossless.dcm", "JPEG2000.dcm",
        "MR_small_RLE.dcm", "SC_rgb_rle_2frame.dcm"}) {
    const fs::path file = mvw::test::sampleData(std::string("pydicom/test_files/") + name);
    expectSame(mvw::io::readVolume(file), readInThisProcess(file), file);
  }
}

TEST(IsolatedDecoder, NativePixelDataNeedsNoChild) {
  const ScopedEnv decoder("MVW_DECODER", "/nonexistent/mvw-decoder");
  EXPECT_NO_THROW(
      (void)mvw::io::readVolume(mvw::test::sampleData("pydicom/test_files/CT_small.dcm")));
  EXPECT_NE(
      errorReading(mvw::test::sampleData(kJpeg))
          .find("MVW_DECODER names /nonexistent/mvw-decoder, which is not an executable file"),
      std::string::npos);
}

// Each fault of the child is the file's error, said naming it; then the same process reads
// the same file through a child that does not fail.
void expectFault(const std::string& fault, const std::string& said) {
  SCOPED_TRACE(fault);
  const fs::path file = mvw::test::sampleData(kJpeg);
  const Volume expected = readInThisProcess(file);
  {
    const ScopedEnv decoder("MVW_DECODER", MVW_DECODER_FAULTS);
    const ScopedEnv how("MVW_TEST_DECODER_FAULT", fault);
    const std::string message = errorReading(file);
    EXPECT_NE(message.find(file.string() + ": the DICOM decoder failed on this file: "),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(said), std::string::npos) << message;
  }
  {
    const ScopedEnv decoder("MVW_DECODER", MVW_DECODER_FAULTS);  // a helper that does not fail
    expectSame(mvw::io::readVolume(file), expected, file);
  }
  expectSame(mvw::io::readVolume(file), expected, file);  // mvw-decoder
}

TEST(IsolatedDecoder, ACrashIsTheFilesError) {
#if defined(__SANITIZE_ADDRESS__)
  expectFault("crash", "it ended (exit status 1)");  // ASan's SEGV handler reports, exits 1
#else
  expectFault("crash", "it crashed (signal 11, SIGSEGV");
#endif
}

TEST(IsolatedDecoder, AHangIsStoppedAtTheTimeLimit) {
  const ScopedEnv seconds("MVW_DECODER_SECONDS", "1");
  const auto start = std::chrono::steady_clock::now();
  expectFault("hang", "it ran past its time limit of 1 s (MVW_DECODER_SECONDS) and was stopped");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(IsolatedDecoder, AMemoryBlowUpStopsAtTheLimit) {
#if defined(__SANITIZE_ADDRESS__)
  // ASan's allocator does not return null: it reports the failed mmap and exits 1.
  expectFault("memory", "it ended (exit status 1)");
#else
  expectFault("memory", "it reached its memory limit of");
#endif
}

TEST(IsolatedDecoder, AnAnswerOfAnotherSizeIsRefused) {
  expectFault("oversize", "where the headers say 100 x 100 x 1 of 3 (VTK type 3, 30000 bytes)");
}

// tests/fuzz/regressions' JPEG whose SOF says 100 x 100 in a 50 x 50 image: GDCM writes 30,000
// bytes into a 7,500-byte buffer. The frame-header checks refuse it before any decoder runs, so
// the faulty helper decodes it behind them, inside the child, then serves the request.
TEST(IsolatedDecoder, AHeapOverflowInGdcmStaysInTheChild) {
  const ScopedEnv file("MVW_TEST_DECODER_OVERFLOW_FILE",
                       (fs::path(MVW_SOURCE_DIR) / "tests/fuzz/regressions/"
                                                   "bad-dicom-jpeg-sof-larger-than-rows.dcm")
                           .string());
#if defined(__SANITIZE_ADDRESS__)
  expectFault("overflow", "it ended (exit status 1)");  // ASan's heap-buffer-overflow report
#else
  // SIGSEGV in the release build (the overwritten heap), SIGABRT where glibc notices first.
  expectFault("overflow", "it crashed (signal");
#endif
}

// tests/fuzz/regressions' JPEG whose frame GDCM cannot decode ("Impossible length": longer than
// 256 x 256 x 3 allows). vtk-dicom ignores GDCM's answer and hands back the buffer GDCM never
// wrote (valgrind: uses of uninitialised values), so the file used to load as an image of
// uninitialised bytes; mvw's reader checks the answer (CheckedDicomReader.h). The file's error,
// with GDCM's reason, in the child and in this process alike.
TEST(IsolatedDecoder, AFrameGdcmCannotDecodeIsTheFilesError) {
  const fs::path file =
      fs::path(MVW_SOURCE_DIR) / "tests/fuzz/regressions/bad-dicom-jpeg-gdcm-decode-fails.dcm";
  const std::string reason = "could not decode the compressed pixel data";
  EXPECT_NE(errorReading(file).find(reason), std::string::npos) << errorReading(file);
  try {
    (void)readInThisProcess(file);
    ADD_FAILURE() << file << " read in this process without an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

}  // namespace
