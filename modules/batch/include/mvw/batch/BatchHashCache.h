#pragma once
// The input hashes a batch run remembers, so that a rerun does not read every input again:
// SHA-256 stays the truth (done.json records it), and a file's hash is reused only while its
// size, modification time (ns) and inode are those it had when it was hashed, as DVC does; a
// folder's (a DICOM series) while every file in it keeps them. One TSV per shard in
// OUT/hashes/ (written atomically, so concurrent Slurm tasks never mix their lines); a run reads
// them all. A file modified less than two seconds before it was hashed is not remembered: a
// file system's coarse clock could give a second write within that time the same stat.
#include <cstdint>
#include <filesystem>
#include <string>
#include <unordered_map>

namespace mvw::batch {

class BatchHashCache {
 public:
  // Remembers nothing and writes nothing: every hash is computed.
  BatchHashCache() = default;

  // Reads every *.tsv in `folder` (none when it does not exist); save() writes folder/fileName.
  // With `verify`, no remembered hash is reused (`mvw batch run --verify`).
  BatchHashCache(std::filesystem::path folder, std::string fileName, bool verify);

  // process::pathSha256 of `path` (a file or a folder), or its remembered hash while its stat is
  // unchanged. Throws InputError as process::pathSha256 does.
  std::string pathSha256(const std::filesystem::path& path, const std::string& role);

  // The same for what must be a file: a folder is refused as process::fileSha256 refuses it.
  std::string fileSha256(const std::filesystem::path& file, const std::string& role);

  // Writes the hashes used since construction (so entries of inputs no longer named drop out),
  // atomically. Nothing without a folder.
  void save() const;

  int hashed() const { return hashed_; }  // computed since construction
  int reused() const { return reused_; }  // taken from the cache since construction

  // The stat a remembered hash stands for ("" when `path` cannot be stat'ed), and the newest
  // modification time within it (ns since the epoch).
  struct Stamp {
    std::string text;
    std::int64_t newestNs = 0;
  };
  static Stamp stamp(const std::filesystem::path& path);

 private:
  struct Entry {
    std::string stamp, sha256;
  };
  std::filesystem::path folder_;
  std::string fileName_;
  bool verify_ = false;
  std::unordered_map<std::string, Entry> known_, used_;
  int hashed_ = 0, reused_ = 0;
};

}  // namespace mvw::batch
