#pragma once
// Two error tiers (docs/design.md#errors): programmer bugs are MVW_CHECKs (Check.h); bad data and
// environment failures are exceptions derived from mvw::Error. exitCodeOf (ExitCode.h) alone
// turns them into exit codes: InputError -> 2 (bad file, bad config), ServiceError -> 3 (a
// server or the network failed), any other Error -> 1 (internal fault).
#include <filesystem>
#include <stdexcept>
#include <string>

namespace mvw {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad input: a file or config that cannot be used. The message always names the file.
class InputError : public Error {
 public:
  InputError(const std::filesystem::path& file, const std::string& problem);
  const std::filesystem::path& file() const { return file_; }
  const std::string& problem() const { return problem_; }

 private:
  std::filesystem::path file_;
  std::string problem_;
};

// A server (PACS, scheduler) that could not be reached, refused, timed out or broke off. The
// message names the server and what it said; never credentials.
class ServiceError : public Error {
 public:
  explicit ServiceError(const std::string& message) : Error(message) {}
};

// Why `path` cannot be opened as a file to read, said as what it is ("no such file or
// directory", "is a symbolic link that leads to nothing (...)", "is a folder, not a file",
// "cannot be read: permission denied"), or "" when it can. Pipes and devices count as readable
// (a config given as <(...) is a pipe).
std::string whyUnreadable(const std::filesystem::path& path);

// Throws InputError(path, whyUnreadable(path)) when there is a reason.
void requireReadable(const std::filesystem::path& path);

}  // namespace mvw
