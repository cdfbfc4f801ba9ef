#include "mvw/io/AtomicFile.h"

#include <unistd.h>

#include <fstream>
#include <string>

#include "mvw/core/Error.h"

namespace mvw::io {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path tmp =
      path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + path.filename().string());
  try {
    write(tmp);
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void writeTextAtomically(const fs::path& path, std::string_view text) {
  writeAtomically(path, [&](const fs::path& tmp) {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    f.flush();
    if (!f) throw Error("cannot write " + path.string());
  });
}

void copyFileAtomically(const fs::path& from, const fs::path& to) {
  writeAtomically(to, [&](const fs::path& tmp) {
    std::error_code ec;
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec)
      throw Error("cannot copy " + from.string() + " to " + to.string() + ": " + ec.message());
  });
}

}  // namespace mvw::io
