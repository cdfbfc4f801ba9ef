#include "DecoderGuard.h"

#include <csignal>
#include <cstring>
#include <string>

#include <unistd.h>

#include "mvw/core/ExitCode.h"

namespace mvw::io::detail {

namespace {

// The message is prepared before the decoder runs: a signal handler may only write() it.
char gMessage[4096];
std::size_t gMessageLength = 0;
int gDepth = 0;
struct sigaction gPrevious[4];
constexpr int kSignals[4] = {SIGABRT, SIGSEGV, SIGBUS, SIGFPE};

void onFatalSignal(int) {
  (void)!::write(STDERR_FILENO, gMessage, gMessageLength);
  ::_exit(kExitBadInput);
}

}  // namespace

DecoderGuard::DecoderGuard(const std::filesystem::path& file, bool active) : active_(active) {
  if (!active_) return;
  if (gDepth++ > 0) return;
  const std::string text =
      "\nmvw: error: " + file.string() +
      ": the DICOM decoder (vtk-dicom / GDCM) gave up on malformed data in this file\n";
  gMessageLength = std::min(text.size(), sizeof gMessage);
  std::memcpy(gMessage, text.data(), gMessageLength);
  struct sigaction action {};
  action.sa_handler = onFatalSignal;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < 4; ++i) ::sigaction(kSignals[i], &action, &gPrevious[i]);
}

DecoderGuard::~DecoderGuard() {
  if (!active_) return;
  if (--gDepth > 0) return;
  for (int i = 0; i < 4; ++i) ::sigaction(kSignals[i], &gPrevious[i], nullptr);
}

}  // namespace mvw::io::detail
