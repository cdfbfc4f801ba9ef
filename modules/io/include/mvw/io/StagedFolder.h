#pragma once
// A command's outputs appear together or not at all: they are written into a temporary folder
// on the destination's file system and moved into place by commit() once every one is whole;
// until then the destination holds what it held before. The one home of that rule for groups
// of files and for folders (AtomicFile.h keeps it for a single file), used by mvw render's views
// (output), register's outputs, convert's image and sidecar, DICOM series output (dicomout) and
// the PACS retrieve (pacs).
#include <filesystem>
#include <string>
#include <vector>

#include "mvw/io/Interrupt.h"

namespace mvw::io {

class StagedFolder {
 public:
  // Where the temporary folder lies. Either way on the destination's file system, so each move
  // into place is a rename.
  enum class Place {
    // Beside the destination, in the nearest folder that exists on the way up from it: nothing
    // is created on the way to the destination before commit(), so a failure leaves no empty
    // folders either. The destination need not exist.
    Beside,
    // A hidden folder inside the destination, which is made at once (with its parents): for a
    // destination whose own folder may be the only one writable (a file's folder, a download
    // folder).
    Inside,
  };
  // What commit() does to the destination.
  enum class Mode {
    // Each staged entry is moved into the destination, made if missing: a file replaces the
    // file of its name, a folder replaces whatever has its name whole (an earlier run's frames
    // do not linger); every other entry the destination held stays.
    Merge,
    // The destination becomes the staged folder: whatever it held before is removed. Beside
    // only.
    Replace,
  };
  struct Options {
    // Names the temporary folder, .mvw-<purpose>-<pid>-<n>[-<destination's name>], so one
    // left behind by a killed process says which command made it. Such a folder (kill -9, a
    // power cut: no handler ran) is removed by the next StagedFolder of its purpose made
    // beside it: each live one is locked by its process (flock, which the kernel releases when
    // the process dies), so one that can be locked and is older than 10 s is abandoned.
    std::string purpose = "staging";
    Place place = Place::Beside;
    Mode mode = Mode::Merge;
    // true: the temporary folder is made by the constructor, so a place that cannot be written
    // is refused before any costly work. false: at the first path(), so a run that fails
    // before it writes anything touches nothing at all.
    bool createNow = true;
  };

  // Throws InputError naming `destination` when it exists and is not a folder, or (createNow,
  // Inside) when the temporary folder cannot be made.
  explicit StagedFolder(const std::filesystem::path& destination);
  StagedFolder(const std::filesystem::path& destination, Options options);
  // Not committed (an exception on the way, or an early return): removes the temporary folder
  // and all it holds; the destination is as it was. Committed: removes what commit() left. A
  // process interrupted by SIGINT or SIGTERM removes it too (io::installInterruptCleanup).
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // The temporary folder to write into (made here on the first call when not createNow).
  const std::filesystem::path& path();
  // The destination, absolute and without a trailing separator.
  const std::filesystem::path& destination() const { return destination_; }

  // Every staged entry into place (Merge: in name order).
  void commit();
  // Merge only: these entries, in this order (a reader that waits for the last one sees the
  // others in place); anything else staged is dropped with the temporary folder. A name not
  // staged is an error. Throws InputError naming the entry a move fails on; the entries moved
  // before it stay moved.
  void commit(const std::vector<std::string>& names);
  bool committed() const { return committed_; }

 private:
  void make();
  void moveIn(const std::string& name);

  std::filesystem::path given_;        // as the caller named it, for messages
  std::filesystem::path destination_;  // absolute, normalised
  std::filesystem::path dir_;          // the temporary folder
  Options options_;
  bool made_ = false;
  bool committed_ = false;
  int lock_ = -1;                   // the temporary folder, flock()ed while this process lives
  RemovedOnInterrupt onInterrupt_;  // Ctrl-C removes the temporary folder too (Interrupt.h)
};

}  // namespace mvw::io
