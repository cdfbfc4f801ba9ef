#include "mvw/core/Error.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

namespace mvw {

InputError::InputError(const std::filesystem::path& file, const std::string& problem)
    : Error(file.string() + ": " + problem), file_(file), problem_(problem) {}

std::string whyUnreadable(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    if (fs::is_symlink(fs::symlink_status(path, ec)))
      return "is a symbolic link that leads to nothing (its target is missing, or the links "
             "form a loop)";
    if (ec && ec != std::errc::no_such_file_or_directory) return "cannot be read: " + ec.message();
    return "no such file or directory";
  }
  if (fs::is_directory(status)) return "is a folder, not a file";
  if (::access(path.c_str(), R_OK) != 0)
    return "cannot be read: " + std::string(std::strerror(errno));
  return "";
}

void requireReadable(const std::filesystem::path& path) {
  if (std::string why = whyUnreadable(path); !why.empty()) throw InputError(path, why);
}

}  // namespace mvw
