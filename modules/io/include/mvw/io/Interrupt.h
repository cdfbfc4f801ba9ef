#pragma once
// Ctrl-C and `kill` (SIGINT, SIGTERM) leave nothing half-written: the one home of mvw's signal
// handling. Every staged output (StagedFolder's temporary folder, AtomicFile's temporary file,
// a batch study's work folder) is registered here while it lives; on SIGINT or SIGTERM the
// handler removes every registered path, says on stderr what it removed and exits with the
// conventional status 128 + the signal (130, 143). The handler is async-signal-safe: the paths
// wait in fixed slots filled before the signal, and it removes them with plain system calls
// (open, getdents64, unlinkat, write, _exit), whichever thread it interrupts.
#include <filesystem>

namespace mvw::io {

// Installs the handler for SIGINT and SIGTERM (once per process; a signal the process was
// started ignoring, as `nohup` does, stays ignored). A process forked afterwards without exec
// (the process pool's launcher) dies of the signal as it would have without the handler.
void installInterruptCleanup();

// While it lives, `path` (a file or a folder, absolute) is removed when the process is
// interrupted, or with Keep named on stderr as kept for the next run to resume (the PACS
// cache's partial series). Registering never fails: past the slots' capacity (256 at once) or
// length (4095 bytes) a path is simply not handled on interrupt (no mvw command stages that
// many).
class RemovedOnInterrupt {
 public:
  enum class Action { Remove, Keep };
  RemovedOnInterrupt() = default;
  explicit RemovedOnInterrupt(const std::filesystem::path& path, Action action = Action::Remove);
  ~RemovedOnInterrupt();
  RemovedOnInterrupt(const RemovedOnInterrupt&) = delete;
  RemovedOnInterrupt& operator=(const RemovedOnInterrupt&) = delete;
  RemovedOnInterrupt(RemovedOnInterrupt&& other) noexcept;
  RemovedOnInterrupt& operator=(RemovedOnInterrupt&& other) noexcept;

  // No longer removed on interrupt (it was moved into place, or removed already).
  void release();

 private:
  int slot_ = -1;
};

}  // namespace mvw::io
