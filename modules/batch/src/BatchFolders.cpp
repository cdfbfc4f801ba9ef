#include "mvw/batch/BatchFolders.h"

#include <fcntl.h>
#include <unistd.h>

#include <vector>

namespace mvw::batch {

namespace fs = std::filesystem;

fs::path workFolder(const fs::path& out, const std::string& id) {
  return out / (".work-" + id + "-" + std::to_string(::getpid()));
}

void removeLeftovers(const fs::path& out, const std::string& id) {
  std::vector<fs::path> stale;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    for (const char* prefix : {".work-", ".old-"}) {
      const std::string p = std::string(prefix) + id + "-";
      if (name.rfind(p, 0) == 0 && name.find('-', p.size()) == std::string::npos)
        stale.push_back(e.path());
    }
  }
  for (const auto& p : stale) fs::remove_all(p);
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
