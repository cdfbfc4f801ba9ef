#pragma once
// Two error tiers (CONVENTIONS.md): programmer bugs are MVW_CHECKs (Check.h); bad data and
// environment failures are exceptions derived from mvw::Error. Only app/ decides exit codes:
// InputError -> 2 (bad file, bad config), any other Error -> 1 (internal fault).
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

}  // namespace mvw
