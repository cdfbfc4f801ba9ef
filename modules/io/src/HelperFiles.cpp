#include "HelperFiles.h"

#include <dlfcn.h>

#include <algorithm>
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
  auto besidePrefix = [&](const fs::path& prefix) {
    for (const fs::path& p :
         {prefix / MVW_INSTALL_LIBDIR / "mvw" / file, prefix / "lib" / "mvw" / file})
      if (std::find(candidates.begin(), candidates.end(), p) == candidates.end())
        candidates.push_back(p);
  };
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) besidePrefix(exe.parent_path().parent_path());
  // A shared object embedding these libraries (the Python module, installed into
  // <prefix>/lib/python3.11/dist-packages): the prefix above the nearest lib folder it lies in,
  // so an install into another prefix finds its own helpers.
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&helperFileCandidates), &self) != 0 && self.dli_fname) {
    const fs::path object = fs::weakly_canonical(self.dli_fname, ec);
    if (!ec && object != exe && object.filename().string().find(".so") != std::string::npos)
      for (fs::path dir = object.parent_path(); dir.has_relative_path(); dir = dir.parent_path())
        if (dir.filename() == "lib" || dir.filename() == "lib64") {
          besidePrefix(dir.parent_path());
          break;
        }
  }
  candidates.push_back(buildPath);
  candidates.push_back(installPath);
  return candidates;
}

}  // namespace mvw::io::detail
