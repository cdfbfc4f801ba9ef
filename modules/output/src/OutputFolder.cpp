#include "mvw/output/OutputFolder.h"

#include <string>
#include <vector>

#include <unistd.h>

#include "mvw/core/Error.h"

namespace mvw::output {

namespace fs = std::filesystem;

namespace {

// The nearest of `path` and its parents that exists (an absolute, normalised path); the names
// of the folders still to be made on the way down to `path`, outermost last, into `missing`.
fs::path nearestExisting(const fs::path& path, std::vector<std::string>& missing) {
  std::error_code ec;
  fs::path existing = path;
  while (!existing.empty() && existing != existing.root_path() && !fs::exists(existing, ec)) {
    if (!existing.filename().empty()) missing.push_back(existing.filename().string());
    existing = existing.parent_path();
  }
  return existing;
}

}  // namespace

void checkOutputFolder(const fs::path& outDir) {
  const fs::path out = fs::absolute(outDir).lexically_normal();
  std::vector<std::string> toMake;
  const fs::path existing = nearestExisting(out, toMake);
  std::error_code ec;
  if (!fs::is_directory(existing, ec))
    throw InputError(outDir, existing.string() + " is not a folder");
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    throw InputError(outDir, "the folder " + existing.string() + " is not writable");
  const long nameMax = ::pathconf(existing.c_str(), _PC_NAME_MAX);
  for (const std::string& name : toMake)
    if (nameMax > 0 && static_cast<long>(name.size()) > nameMax)
      throw InputError(outDir, "the folder name '" + name.substr(0, 40) + "...' is " +
                                   std::to_string(name.size()) +
                                   " characters, more than the file system's " +
                                   std::to_string(nameMax));
}

}  // namespace mvw::output
