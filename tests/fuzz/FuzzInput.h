#pragma once
// Shared by the libFuzzer targets: the readers take paths, so each input is written to a
// file in a per-process scratch folder under the name the reader's format detection expects.
// Bad input must end in mvw::InputError; any other exception is an internal fault on bad
// input (exit 1 from the CLI) and is reported as a finding, as are crashes and sanitizer
// reports.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <new>
#include <string>

#include "mvw/core/Error.h"

namespace mvw::fuzz {

// Far below libFuzzer's 2 GiB RSS limit: a header may claim any size, the reader must refuse
// what exceeds the limit before allocating it (ReadOptions::maxBytes).
inline constexpr std::size_t kMaxBytes = std::size_t(64) << 20;

// The harness's inputs as files, in a folder of the process's own, removed when it exits.
inline const std::filesystem::path& scratch() {
  struct Folder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("mvw-fuzz-" + std::to_string(::getpid()));
    Folder() { std::filesystem::create_directories(path); }
    ~Folder() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Folder folder;
  return folder.path;
}

inline std::filesystem::path writeInput(const std::uint8_t* data, std::size_t size,
                                        const std::string& name) {
  const auto p = scratch() / name;
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return p;
}

namespace detail {

template <class F>
void runAllowingNone(F& run) {
  run();
}

template <class First, class... Rest, class F>
void runAllowing(F& run) {
  try {
    if constexpr (sizeof...(Rest) == 0)
      runAllowingNone(run);
    else
      runAllowing<Rest...>(run);
  } catch (const First& e) {
    // An expected end of bad input; said with MVW_FUZZ_VERBOSE=1, to check what seeds reach.
    if (const char* v = std::getenv("MVW_FUZZ_VERBOSE"); v && *v == '1')
      std::fprintf(stderr, "refused: %s\n", e.what());
  }
}

}  // namespace detail

// Runs `run`; the exception types named are the parser's refusals of bad input, anything else
// thrown is a finding.
template <class... Refusals, class F>
void expectOnly(F&& run) {
  try {
    if constexpr (sizeof...(Refusals) == 0)
      detail::runAllowingNone(run);
    else
      detail::runAllowing<Refusals...>(run);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mvw fuzz: bad input ended in an exception that is not a refusal: %s\n",
                 e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "mvw fuzz: bad input ended in an exception that is not a refusal\n");
    std::abort();
  }
}

template <class F>
void expectInputErrorOnly(F&& read) {
  expectOnly<InputError>(read);
}

// A finding that is not a crash: a property the harness checks failed.
[[noreturn]] inline void finding(const char* what) {
  std::fprintf(stderr, "mvw fuzz: %s\n", what);
  std::abort();
}

}  // namespace mvw::fuzz
