#include "mvw/io/AtomicFile.h"

#include <unistd.h>

#include <fstream>
#include <string>

#include "mvw/core/Error.h"
#include "mvw/io/Interrupt.h"

namespace mvw::io {

namespace fs = std::filesystem;

void writeAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  const fs::path tmp =
      path.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + path.filename().string());
  const RemovedOnInterrupt onInterrupt(fs::absolute(tmp));  // Ctrl-C: no .tmp-* is left
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
    f.close();  // a full disk may only say so when the last buffer goes out
    if (!f) throw InputError(path, "cannot write (disk full or not writable?)");
  });
}

void copyFileAtomically(const fs::path& from, const fs::path& to) {
  writeAtomically(to, [&](const fs::path& tmp) {
    std::error_code ec;
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw InputError(to, "cannot copy " + from.string() + " here: " + ec.message());
  });
}

}  // namespace mvw::io
