#pragma once
// Shared helpers for the unit tests: a scratch folder per test and the sample-data root.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace mvw::test {

inline std::filesystem::path scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::temp_directory_path() /
             ("mvw-test-" + std::string(info->test_suite_name()) + "-" + info->name());
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
