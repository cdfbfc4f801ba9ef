#include "mvw/batch/BatchHashCache.h"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "mvw/io/AtomicFile.h"
#include "mvw/process/Sha256.h"

namespace mvw::batch {

namespace fs = std::filesystem;

namespace {

const char* const kHeader =
    "# mvw batch: input hashes (sha256, stat when hashed, path); reused while the stat holds\n";

// A modification this recent may share its stat with a write that follows it (coarse clocks).
constexpr std::int64_t kRacyNs = 2'000'000'000;

bool statOf(const fs::path& path, struct stat& st) { return ::stat(path.c_str(), &st) == 0; }

std::int64_t mtimeNs(const struct stat& st) {
  return static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
}

std::string fileStamp(const struct stat& st) {
  return std::to_string(st.st_size) + ":" + std::to_string(mtimeNs(st)) + ":" +
         std::to_string(st.st_ino);
}

std::int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

BatchHashCache::BatchHashCache(fs::path folder, std::string fileName, bool verify)
    : folder_(std::move(folder)), fileName_(std::move(fileName)), verify_(verify) {
  std::error_code ec;
  if (verify_ || !fs::is_directory(folder_, ec)) return;
  for (const auto& e : fs::directory_iterator(folder_, ec)) {
    if (e.path().extension() != ".tsv") continue;
    std::ifstream in(e.path());
    std::string line;
    while (std::getline(in, line)) {
      const auto a = line.find('\t');
      const auto b = a == std::string::npos ? a : line.find('\t', a + 1);
      if (line.empty() || line[0] == '#' || b == std::string::npos) continue;
      known_[line.substr(b + 1)] = {line.substr(a + 1, b - a - 1), line.substr(0, a)};
    }
  }
}

BatchHashCache::Stamp BatchHashCache::stamp(const fs::path& path) {
  struct stat st {};
  if (!statOf(path, st)) return {};
  if (!S_ISDIR(st.st_mode)) return {"f:" + fileStamp(st), mtimeNs(st)};
  // A folder: every file in it and below, by name, with its stat.
  std::vector<std::pair<std::string, std::string>> files;
  std::int64_t newest = 0;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(path, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    struct stat f {};
    if (!statOf(it->path(), f) || !S_ISREG(f.st_mode)) continue;
    files.emplace_back(it->path().lexically_relative(path).generic_string(), fileStamp(f));
    newest = std::max(newest, mtimeNs(f));
  }
  if (ec) return {};
  std::sort(files.begin(), files.end());
  process::Sha256 sum;
  for (const auto& [name, s] : files) {
    sum.add(name.data(), name.size() + 1);  // with its NUL: names cannot run into stamps
    sum.add(s.data(), s.size() + 1);
  }
  return {"d:" + std::to_string(st.st_ino) + ":" + sum.hex(), newest};
}

std::string BatchHashCache::pathSha256(const fs::path& path, const std::string& role) {
  const std::string key = path.string();
  const Stamp now = stamp(path);
  if (!now.text.empty()) {
    for (auto* map : {&used_, &known_}) {
      const auto it = map->find(key);
      if (it != map->end() && it->second.stamp == now.text) {
        ++reused_;
        used_[key] = it->second;
        return it->second.sha256;
      }
    }
  }
  const std::int64_t hashedAt = nowNs();
  std::string sha = process::pathSha256(path, role);
  ++hashed_;
  // Remembered only when the stat it was taken with is old enough to be trusted, and the path
  // fits a TSV line.
  if (!now.text.empty() && hashedAt - now.newestNs >= kRacyNs &&
      key.find_first_of("\t\n\r") == std::string::npos && stamp(path).text == now.text)
    used_[key] = {now.text, sha};
  return sha;
}

std::string BatchHashCache::fileSha256(const fs::path& file, const std::string& role) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) return process::fileSha256(file, role);
  return pathSha256(file, role);
}

void BatchHashCache::save() const {
  if (folder_.empty()) return;
  std::vector<const std::pair<const std::string, Entry>*> entries;
  for (const auto& e : used_) entries.push_back(&e);
  std::sort(entries.begin(), entries.end(),
            [](const auto* a, const auto* b) { return a->first < b->first; });
  std::ostringstream text;
  text << kHeader;
  for (const auto* e : entries)
    text << e->second.sha256 << '\t' << e->second.stamp << '\t' << e->first << '\n';
  fs::create_directories(folder_);
  io::writeTextAtomically(folder_ / fileName_, text.str());
}

}  // namespace mvw::batch
