#include "IsolatedDecoder.h"

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <unistd.h>

#include <vtkDICOMMetaData.h>
#include <vtkDICOMReader.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>

#include "CheckedDicomReader.h"
#include "HelperFiles.h"
#include "VtkBridge.h"
#include "VtkMessages.h"
#include "mvw/core/Error.h"
#include "mvw/core/Format.h"
#include "mvw/process/Helper.h"
#include "mvw/process/ProcessPool.h"
#include "mvw/process/Wire.h"

namespace mvw::io::detail {

namespace fs = std::filesystem;

namespace {

// Both ends are one build; a helper of another (an older install found first) says so.
constexpr std::uint32_t kProtocol = 0x6d766431;  // "mvd1"
enum class Answer : std::uint8_t { Voxels = 1, ReaderError = 2, OtherBuild = 3 };
// The helper's exit status when an allocation failed: its memory limit was reached.
constexpr int kOutOfMemory = 4;

bool isNativeOrDeflated(const std::string& ts) {
  // Implicit VR LE (also no meta header), explicit VR LE, explicit VR BE, deflated (inflated by
  // DeflatedDicom before the reader sees it).
  return ts.empty() || ts == "1.2.840.10008.1.2" || ts == "1.2.840.10008.1.2.1" ||
         ts == "1.2.840.10008.1.2.2" || ts == "1.2.840.10008.1.2.1.99";
}

// The helper: $MVW_DECODER, else as HelperFiles.h says.
fs::path helperExecutable(const fs::path& file) {
  std::string tried;
  const char* chosen = std::getenv("MVW_DECODER");
  for (const fs::path& candidate : helperFileCandidates(
           "MVW_DECODER", MVW_DECODER_FILE, MVW_DECODER_BUILD_PATH, MVW_DECODER_INSTALL_PATH)) {
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (chosen && *chosen)
      throw InputError(file, "cannot decode its compressed pixel data: MVW_DECODER names " +
                                 candidate.string() + ", which is not an executable file");
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  throw InputError(file, std::string("cannot decode its compressed pixel data: mvw's decoder "
                                     "helper (") +
                             MVW_DECODER_FILE + ") is not installed; looked in " + tried);
}

// A number from the environment (a user's override of a limit), or `fallback`.
double fromEnvironment(const char* name, double fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return end && *end == '\0' && value > 0 ? value : fallback;
}

std::string signalName(int signal) {
  const char* name = ::sigabbrev_np(signal);
  const char* what = ::strsignal(signal);
  return "signal " + std::to_string(signal) + (name ? std::string(", SIG") + name : "") +
         (what ? std::string(", ") + what : "");
}

#if defined(__SANITIZE_ADDRESS__)
constexpr std::uint64_t kSanitizerSlack = std::uint64_t(2) << 30;  // ASan's quarantine, redzones
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr std::uint64_t kSanitizerSlack = std::uint64_t(2) << 30;
#else
constexpr std::uint64_t kSanitizerSlack = 0;
#endif
#else
constexpr std::uint64_t kSanitizerSlack = 0;
#endif

}  // namespace

bool hasCompressedPixelData(vtkDICOMMetaData* meta) {
  for (int i = 0; i < meta->GetNumberOfInstances(); ++i)
    if (!isNativeOrDeflated(meta->Get(i, DC::TransferSyntaxUID).AsString())) return true;
  return false;
}

Volume decodeInChild(vtkDICOMReader* reader, const fs::path& input, const fs::path& first) {
  vtkStringArray* files = reader->GetFileNames();
  const vtkIdType fileCount = files ? files->GetNumberOfValues() : 0;
  // What the headers read here say the voxels are: the child must send exactly this.
  vtkInformation* info = reader->GetOutputInformation(0);
  const auto [dims, components, vtkType] = voxelLayout(info);
  Volume volume = volumeOfVtkType(dims, components, vtkType, first);

  // Decoder faults are said of the file, or of the series when it has several files.
  const bool oneFile = fileCount == 1;
  const fs::path named = oneFile ? first : input;
  const std::string what =
      oneFile ? std::string("this file")
              : "a file of this series (" + countOf(fileCount, "compressed file") + ")";
  auto failed = [&](const std::string& why) {
    return InputError(named, "the DICOM decoder failed on " + what + ": " + why +
                                 "; it ran in a process of its own, so nothing else was affected");
  };

  std::uint64_t fileBytes = 0;
  for (vtkIdType i = 0; i < fileCount; ++i) {
    std::error_code ec;
    fileBytes += fs::file_size(files->GetValue(i).c_str(), ec);
  }
  process::HelperLimits limits;
  // Its output, the reader's buffers for one file's frames and the files themselves, twice over,
  // and 256 MiB for what any run of it maps.
  const std::uint64_t memoryMiB = static_cast<std::uint64_t>(fromEnvironment(
      "MVW_DECODER_MEMORY_MIB",
      static_cast<double>(
          (2 * (volume.byteSize() + fileBytes) + (std::uint64_t(256) << 20) + kSanitizerSlack) >>
          20)));
  limits.memoryBytes = memoryMiB << 20;
  // 30 s, and 1 s for every 4 MiB of voxels (OpenJPEG decodes 10-30 MB/s on one core).
  limits.seconds = fromEnvironment("MVW_DECODER_SECONDS",
                                   30.0 + static_cast<double>(volume.byteSize()) / (4 << 20));

  const fs::path exe = helperExecutable(named);
  const char* stderrChoice = std::getenv("MVW_DECODER_STDERR");
  process::HelperProcess child(exe, {}, limits, stderrChoice && *stderrChoice);
  const auto deadline = child.deadline();
  const int fd = child.socket();
  auto ended = [&]() -> InputError {
    const int status = child.wait();
    if (status == process::kTimedOut)
      return failed("it ran past its time limit of " + std::to_string(std::lround(limits.seconds)) +
                    " s (MVW_DECODER_SECONDS) and was stopped");
    if (status == kOutOfMemory || status == 128 + SIGXCPU)
      return failed(status == kOutOfMemory
                        ? "it reached its memory limit of " + std::to_string(memoryMiB) +
                              " MiB (MVW_DECODER_MEMORY_MIB)"
                        : "it used up its CPU time limit of " +
                              std::to_string(std::lround(limits.seconds)) + " s");
    if (status > 128) return failed("it crashed (" + signalName(status - 128) + ")");
    return failed("it ended (exit status " + std::to_string(status) +
                  ") before its answer was whole");
  };
  try {
    if (!child.started()) throw ended();
    process::Message request;
    request.put(kProtocol);
    request.put(static_cast<std::uint8_t>(reader->GetAutoRescale() ? 1 : 0));
    const char* stack = reader->GetDesiredStackID();
    request.put(std::string(stack ? stack : ""));
    request.put(static_cast<std::uint64_t>(fileCount));
    for (vtkIdType i = 0; i < fileCount; ++i) request.put(std::string(files->GetValue(i).c_str()));
    if (!request.send(fd)) throw ended();

    Answer answer{};
    if (!process::receiveAllBy(fd, &answer, sizeof answer, deadline)) throw ended();
    if (answer == Answer::ReaderError || answer == Answer::OtherBuild) {
      std::uint64_t size = 0;
      std::string text;
      if (!process::receiveAllBy(fd, &size, sizeof size, deadline) || size > 4096) throw ended();
      text.resize(size);
      if (size > 0 && !process::receiveAllBy(fd, text.data(), size, deadline)) throw ended();
      child.wait();
      if (answer == Answer::OtherBuild)
        throw InputError(named, "cannot decode its compressed pixel data: " + exe.string() +
                                    " is the decoder helper of another mvw build");
      throw InputError(first, "cannot read the DICOM pixel data: " + printable(text));
    }
    if (answer != Answer::Voxels) throw failed("its answer was not one it may give");
    std::int32_t sent[5];  // dims, components, VTK type
    std::uint64_t bytes = 0;
    if (!process::receiveAllBy(fd, sent, sizeof sent, deadline) ||
        !process::receiveAllBy(fd, &bytes, sizeof bytes, deadline))
      throw ended();
    if (sent[0] != dims.x || sent[1] != dims.y || sent[2] != dims.z || sent[3] != components ||
        sent[4] != vtkType || bytes != volume.byteSize())
      throw failed("it decoded " + std::to_string(sent[0]) + " x " + std::to_string(sent[1]) +
                   " x " + std::to_string(sent[2]) + " voxels of " + std::to_string(sent[3]) +
                   " components (VTK type " + std::to_string(sent[4]) + ", " +
                   std::to_string(bytes) + " bytes) where the headers say " +
                   std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " +
                   std::to_string(dims.z) + " of " + std::to_string(components) + " (VTK type " +
                   std::to_string(vtkType) + ", " + std::to_string(volume.byteSize()) + " bytes)");
    if (!process::receiveAllBy(fd, volume.data(), volume.byteSize(), deadline)) throw ended();
    // Its last word: nothing more, then exit 0.
    char extra = 0;
    if (process::receiveAllBy(fd, &extra, 1, deadline))
      throw failed("it sent more than the " + std::to_string(volume.byteSize()) +
                   " bytes the headers ask for");
    if (const int status = child.wait(); status != 0) {
      (void)status;
      throw ended();
    }
  } catch (const process::WireTimeout&) {
    child.kill();
    throw failed("it ran past its time limit of " + std::to_string(std::lround(limits.seconds)) +
                 " s (MVW_DECODER_SECONDS) and was stopped");
  }
  return volume;
}

int decoderMain(int, char**) {
  const int fd = process::helperSocket();
  if (fd < 0) {
    const char text[] =
        "mvw-decoder decodes compressed DICOM pixel data for mvw in a process of its own; mvw "
        "starts it. It is not a command.\n";
    (void)!::write(STDERR_FILENO, text, sizeof text - 1);
    return 1;
  }
  serveDecoder(fd);
}

void serveDecoder(int fd, const std::function<void(int fd)>& beforeDecoding) {
  try {
    std::uint32_t protocol = 0;
    std::uint8_t autoRescale = 0;
    std::string stack;
    std::uint64_t count = 0;
    if (!process::receive(fd, protocol)) ::_exit(1);
    if (protocol != kProtocol) {
      process::Message m;
      m.put(Answer::OtherBuild);
      m.put(std::string("protocol"));
      m.send(fd);
      ::_exit(0);
    }
    if (!process::receive(fd, autoRescale) || !process::receive(fd, stack, 4096) ||
        !process::receive(fd, count))
      ::_exit(1);
    vtkNew<vtkStringArray> files;
    for (std::uint64_t i = 0; i < count; ++i) {
      std::string name;
      if (!process::receive(fd, name, 65536)) ::_exit(1);
      files->InsertNextValue(name);
    }
    if (beforeDecoding) beforeDecoding(fd);
    VtkMessageScope messages;
    vtkNew<CheckedDicomReader> reader;
    // As DicomSeries.cpp's readSeries configures its reader.
    reader->SetFileNames(files);
    reader->SetMemoryRowOrderToFileNative();
    reader->TimeAsVectorOn();
    reader->SetAutoRescale(autoRescale != 0 ? 1 : 0);
    if (!stack.empty()) reader->SetDesiredStackID(stack.c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
    if (!messages.firstError().empty() || reader->GetErrorCode() != 0 || !scalars) {
      std::string why = messages.firstError();
      if (why.empty()) why = "error code " + std::to_string(reader->GetErrorCode());
      process::Message m;
      m.put(Answer::ReaderError);
      m.put(why.substr(0, 4096));
      m.send(fd);
      ::_exit(0);
    }
    int d[3];
    image->GetDimensions(d);
    const std::int32_t sent[5] = {d[0], d[1], d[2], image->GetNumberOfScalarComponents(),
                                  image->GetScalarType()};
    const std::uint64_t bytes = static_cast<std::uint64_t>(scalars->GetNumberOfValues()) *
                                static_cast<std::uint64_t>(scalars->GetDataTypeSize());
    process::Message m;
    m.put(Answer::Voxels);
    m.put(sent);
    m.put(bytes);
    if (!m.send(fd) || !process::sendAll(fd, scalars->GetVoidPointer(0), bytes)) ::_exit(1);
  } catch (const std::bad_alloc&) {
    ::_exit(kOutOfMemory);
  }
  // _exit: no static destructors, and no leak check of a sanitizer build (GDCM's own leaks are
  // not this run's answer).
  ::_exit(0);
}

}  // namespace mvw::io::detail
