#include "HelperFiles.h"

#include <cstdlib>

namespace mvw::io::detail {

namespace fs = std::filesystem;

std::vector<fs::path> helperFileCandidates(const char* envVar, const std::string& file,
                                           const fs::path& buildPath, const fs::path& installPath) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv(envVar); env && *env) {
    candidates.emplace_back(env);
    return candidates;
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path prefix = exe.parent_path().parent_path();
    candidates.push_back(prefix / MVW_INSTALL_LIBDIR / "mvw" / file);
    candidates.push_back(prefix / "lib" / "mvw" / file);
  }
  candidates.push_back(buildPath);
  candidates.push_back(installPath);
  return candidates;
}

}  // namespace mvw::io::detail
