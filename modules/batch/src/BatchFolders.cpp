#include "mvw/batch/BatchFolders.h"

#include <fcntl.h>
#include <unistd.h>

#include <vector>

namespace mvw::batch {

namespace fs = std::filesystem;

fs::path workFolder(const fs::path& out, const std::string& id) {
  return out / (".work-" + id + "-" + std::to_string(::getpid()));
}

Leftovers findLeftovers(const fs::path& out) {
  Leftovers found;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    for (const std::string prefix : {".work-", ".old-"}) {
      // The id is what lies between the prefix and the last '-' (the pid follows it).
      const auto dash = name.rfind('-');
      if (name.rfind(prefix, 0) == 0 && dash != std::string::npos && dash >= prefix.size())
        found[name.substr(prefix.size(), dash - prefix.size())].push_back(e.path());
    }
  }
  return found;
}

void removeLeftovers(const Leftovers& leftovers, const std::string& id) {
  const auto it = leftovers.find(id);
  if (it == leftovers.end()) return;
  for (const auto& p : it->second) fs::remove_all(p);
}

void removeLeftovers(const fs::path& out, const std::string& id) {
  removeLeftovers(findLeftovers(out), id);
}

void publish(const fs::path& work, const fs::path& out, const std::string& id) {
  const fs::path target = out / id;
  const fs::path old = out / (".old-" + id + "-" + std::to_string(::getpid()));
  if (fs::exists(target)) fs::rename(target, old);
  fs::rename(work, target);
  if (fs::exists(old)) fs::remove_all(old);
  // The renames reach the disk before a later run trusts them.
  const int fd = ::open(out.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace mvw::batch
