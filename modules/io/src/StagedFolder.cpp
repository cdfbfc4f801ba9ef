#include "mvw/io/StagedFolder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <utility>
#include <vector>

#include "mvw/core/Check.h"
#include "mvw/core/Error.h"

namespace mvw::io {

namespace fs = std::filesystem;

namespace {

// The nearest of `path` and its parents that exists.
fs::path nearestExisting(fs::path path) {
  std::error_code ec;
  while (!path.empty() && path != path.root_path() && !fs::exists(path, ec))
    path = path.parent_path();
  return path;
}

// Two staged folders of one process (threads, or one command staging twice) never share a name;
// the process id keeps processes apart.
std::string uniqueName(const std::string& purpose) {
  static std::atomic<unsigned> counter{0};
  return ".mvw-" + purpose + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

// Whether `dir` lies on a local file system, where flock() is seen by every process that can
// see the folder. On NFS, SMB or FUSE a lock may hold only on the host that took it, so a live
// process on another node (a Slurm task writing into a shared OUT) could look abandoned.
bool onLocalFileSystem(const fs::path& dir) {
  struct statfs info {};
  if (::statfs(dir.c_str(), &info) != 0) return false;
  switch (static_cast<unsigned long>(info.f_type)) {
    case 0xEF53UL:      // ext2, ext3, ext4
    case 0x58465342UL:  // xfs
    case 0x9123683EUL:  // btrfs
    case 0x01021994UL:  // tmpfs
    case 0x794C7630UL:  // overlayfs (containers)
    case 0x2FC12FC1UL:  // zfs
    case 0xF2F52010UL:  // f2fs
      return true;
    default:
      return false;
  }
}

// The temporary folders of `purpose` in `parent` that killed processes left: named as
// uniqueName names them, not `keep`, older than 10 s (the moment between a live process's
// mkdir and its flock), and not locked by a live process. Only on a local file system (above);
// elsewhere they stay, as they did before.
void removeAbandoned(const fs::path& parent, const std::string& purpose, const fs::path& keep) {
  if (!onLocalFileSystem(parent)) return;
  const std::string prefix = ".mvw-" + purpose + "-";
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || it->path() == keep) continue;
    std::size_t digits = prefix.size();
    while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[digits]))) ++digits;
    if (digits == prefix.size() || digits >= name.size() || name[digits] != '-') continue;
    std::error_code entryError;
    if (it->is_symlink(entryError) || !it->is_directory(entryError)) continue;
    const auto written = fs::last_write_time(it->path(), entryError);
    if (entryError || fs::file_time_type::clock::now() - written < std::chrono::seconds(10))
      continue;
    const int fd = ::open(it->path().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) continue;
    // Removed while locked, and only if the name still holds the folder locked (not one a new
    // process made there since: it would have replaced it first).
    struct stat locked {
    }, named{};
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstat(fd, &locked) == 0 &&
        ::lstat(it->path().c_str(), &named) == 0 && locked.st_ino == named.st_ino &&
        locked.st_dev == named.st_dev)
      fs::remove_all(it->path(), entryError);
    ::close(fd);
  }
}

}  // namespace

StagedFolder::StagedFolder(const fs::path& destination) : StagedFolder(destination, Options{}) {}

StagedFolder::StagedFolder(const fs::path& destination, Options options)
    : given_(destination), options_(std::move(options)) {
  MVW_CHECK(options_.mode == Mode::Merge || options_.place == Place::Beside);
  destination_ = fs::absolute(destination).lexically_normal();
  if (destination_.filename().empty()) destination_ = destination_.parent_path();  // "out/"
  std::error_code ec;
  if (fs::exists(destination_, ec) && !fs::is_directory(destination_, ec))
    throw InputError(given_, "exists and is not a folder");
  if (options_.place == Place::Inside) {
    fs::create_directories(destination_, ec);
    if (ec)
      throw InputError(given_, "cannot be written: cannot make the folder (" + ec.message() + ")");
    dir_ = destination_ / uniqueName(options_.purpose);
  } else {
    dir_ = nearestExisting(destination_.parent_path()) /
           (uniqueName(options_.purpose) + "-" + destination_.filename().string());
  }
  if (options_.createNow) make();
}

StagedFolder::~StagedFolder() {
  std::error_code ec;
  if (made_) fs::remove_all(dir_, ec);  // after a Replace commit, nothing is left at dir_
  if (lock_ >= 0) ::close(lock_);
}

const fs::path& StagedFolder::path() {
  if (!made_) make();
  return dir_;
}

void StagedFolder::make() {
  std::error_code ec;
  fs::remove_all(dir_, ec);  // left by a killed process that had this process id
  if (!fs::create_directory(dir_, ec))
    throw InputError(given_, "cannot be written: no folder can be made in " +
                                 dir_.parent_path().string() + " (" +
                                 (ec ? ec.message() : std::string("it exists")) + ")");
  made_ = true;
  onInterrupt_ = RemovedOnInterrupt(dir_);
  // Locked while this process lives (released by the kernel however it ends), so that a later
  // run tells this folder from one a killed process left; then those are removed.
  lock_ = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_ >= 0) ::flock(lock_, LOCK_EX | LOCK_NB);
  removeAbandoned(dir_.parent_path(), options_.purpose, dir_);
}

void StagedFolder::moveIn(const std::string& name) {
  const fs::path from = dir_ / name, to = destination_ / name;
  std::error_code ec;
  if (fs::is_directory(from, ec)) fs::remove_all(to, ec);  // an earlier run's
  fs::rename(from, to, ec);
  if (ec) throw InputError(given_ / name, "cannot be moved into place: " + ec.message());
}

void StagedFolder::commit() {
  path();
  if (options_.mode == Mode::Replace) {
    std::error_code ec;
    fs::create_directories(destination_.parent_path(), ec);
    if (!ec) fs::remove_all(destination_, ec);
    if (!ec) fs::rename(dir_, destination_, ec);
    if (ec) throw InputError(given_, "cannot be moved into place: " + ec.message());
    committed_ = true;
    return;
  }
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  commit(names);
}

void StagedFolder::commit(const std::vector<std::string>& names) {
  MVW_CHECK(options_.mode == Mode::Merge);
  path();
  std::error_code ec;
  fs::create_directories(destination_, ec);
  if (ec) throw InputError(given_, "cannot make the output folder: " + ec.message());
  for (const std::string& name : names) moveIn(name);
  committed_ = true;
}

}  // namespace mvw::io
