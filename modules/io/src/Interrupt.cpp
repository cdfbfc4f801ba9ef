#include "mvw/io/Interrupt.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace mvw::io {

namespace {

constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 4096;
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };

// Filled before any signal, read by the handler: fixed storage, lock-free states.
struct Slot {
  std::atomic<int> state{kFree};
  bool keep = false;
  char path[kPathBytes];
};
Slot slots[kSlots];
std::atomic<pid_t> installedBy{0};
volatile std::sig_atomic_t handling = 0;

void say(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<std::size_t>(n);
  }
}

// Removes `name` in the folder `dirFd` (a file, or a folder with all it holds) with system calls
// only. A file another thread writes while this runs may appear after the folder was read: the
// folder is read again until a pass removes nothing.
void removeAt(int dirFd, const char* name, int depth) {
  if (::unlinkat(dirFd, name, 0) == 0 || errno == ENOENT) return;
  if (depth > 32) return;
  const int fd = ::openat(dirFd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  for (int pass = 0; pass < 8; ++pass) {
    bool removed = false;
    ::lseek(fd, 0, SEEK_SET);
    for (;;) {
      const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
      if (n <= 0) break;
      for (long at = 0; at < n;) {
        const auto* entry = reinterpret_cast<const struct dirent64*>(buf + at);
        at += entry->d_reclen;
        const char* child = entry->d_name;
        if (std::strcmp(child, ".") == 0 || std::strcmp(child, "..") == 0) continue;
        removeAt(fd, child, depth + 1);
        removed = true;
      }
    }
    if (!removed) break;
  }
  ::close(fd);
  ::unlinkat(dirFd, name, AT_REMOVEDIR);
}

extern "C" void onInterrupt(int sig) {
  if (::getpid() != installedBy.load()) {  // a fork without exec: die as without the handler
    std::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  if (handling) return;  // the second Ctrl-C while the first cleans up
  handling = 1;
  const char* name = sig == SIGINT ? "SIGINT" : "SIGTERM";
  int said = 0;
  for (Slot& slot : slots) {
    if (slot.state.load() != kLive) continue;
    say("mvw: interrupted (");
    say(name);
    if (slot.keep) {
      say("): kept ");
      say(slot.path);
      say(" for the next run to resume\n");
    } else {
      removeAt(AT_FDCWD, slot.path, 0);
      say("): removed the unfinished ");
      say(slot.path);
      say("\n");
    }
    ++said;
  }
  if (said == 0) {
    say("mvw: interrupted (");
    say(name);
    say("): nothing unfinished was left behind\n");
  }
  ::_exit(128 + sig);
}

}  // namespace

void installInterruptCleanup() {
  installedBy.store(::getpid());
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaddset(&action.sa_mask, SIGINT);
  sigaddset(&action.sa_mask, SIGTERM);
  for (const int sig : {SIGINT, SIGTERM}) {
    struct sigaction before {};
    if (::sigaction(sig, nullptr, &before) == 0 && before.sa_handler == SIG_IGN) continue;
    ::sigaction(sig, &action, nullptr);
  }
}

RemovedOnInterrupt::RemovedOnInterrupt(const std::filesystem::path& path, Action action) {
  const std::string& text = path.native();
  if (text.size() >= kPathBytes) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(slots[i].path, text.c_str(), text.size() + 1);
    slots[i].keep = action == Action::Keep;
    slots[i].state.store(kLive);
    slot_ = i;
    return;
  }
}

RemovedOnInterrupt::~RemovedOnInterrupt() { release(); }

RemovedOnInterrupt::RemovedOnInterrupt(RemovedOnInterrupt&& other) noexcept : slot_(other.slot_) {
  other.slot_ = -1;
}

RemovedOnInterrupt& RemovedOnInterrupt::operator=(RemovedOnInterrupt&& other) noexcept {
  if (this != &other) {
    release();
    slot_ = other.slot_;
    other.slot_ = -1;
  }
  return *this;
}

void RemovedOnInterrupt::release() {
  if (slot_ >= 0) slots[slot_].state.store(kFree);
  slot_ = -1;
}

}  // namespace mvw::io
