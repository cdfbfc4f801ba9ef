#pragma once
// Shared helpers for the unit tests: a scratch folder per test and the sample-data root.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

namespace mvw::test {

// Named by the process too: two checkouts' test runs on one machine (or CTest's parallel
// jobs) never share a folder.
// A parameterised test's names hold '/' ("Formats/RoundTrip", "X/0"): replaced, so the folder
// is one level under the temporary folder and removing it leaves nothing behind.
inline std::filesystem::path scratchDirOf(const ::testing::TestInfo& info) {
  std::string name = "mvw-test-" + std::string(info.test_suite_name()) + "-" + info.name() + "-" +
                     std::to_string(::getpid());
  std::replace(name.begin(), name.end(), '/', '_');
  return std::filesystem::temp_directory_path() / name;
}

// Removes a test's scratch folder when the test ends; a failed test's folder stays for a look,
// and its path is printed.
class ScratchCleaner : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& info) override {
    const std::filesystem::path dir = scratchDirOf(info);
    std::error_code ec;
    if (!std::filesystem::exists(dir, ec)) return;
    if (info.result() != nullptr && info.result()->Failed())
      std::cerr << "the failed test's files are kept in " << dir.string() << "\n";
    else
      std::filesystem::remove_all(dir, ec);
  }
};

// Installed once per test program, before main (gtest_main) runs the tests.
inline const bool kScratchCleanerInstalled = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new ScratchCleaner);
  return true;
}();

// An empty folder of the running test's own, removed when the test passes.
inline std::filesystem::path scratchDir() {
  const auto dir = scratchDirOf(*::testing::UnitTest::GetInstance()->current_test_info());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The fetched sample data. A missing file fails the test: CI never skips data tests.
inline std::filesystem::path sampleData(const std::string& relative) {
  const auto p = std::filesystem::path(MVW_DATA_DIR) / relative;
  if (!std::filesystem::exists(p))
    ADD_FAILURE() << p << " is missing: run scripts/fetch-sample-data";
  return p;
}

}  // namespace mvw::test
