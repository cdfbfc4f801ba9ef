#include "mvw/io/StagedFolder.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <utility>

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
