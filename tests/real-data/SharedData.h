#pragma once
// The real scanner data in ../shared/data (MVW_SHARED_DATA_DIR). A test that needs it starts
// with MVW_REQUIRE_SHARED_DATA("pet-fdg-wholebody"), which skips the test with a message naming
// the folder where it is absent (a user's fresh clone) and gives its path otherwise.
#include <filesystem>

#include <gtest/gtest.h>

namespace mvw::test {

inline std::filesystem::path sharedDataRoot() { return MVW_SHARED_DATA_DIR; }

}  // namespace mvw::test

#define MVW_REQUIRE_SHARED_DATA(relative)                                       \
  [&] {                                                                         \
    const auto mvwSharedPath = ::mvw::test::sharedDataRoot() / (relative);      \
    if (!std::filesystem::exists(mvwSharedPath))                                \
      GTEST_SKIP() << "../shared/data is absent (" << mvwSharedPath.string()    \
                   << " not found): the real-data tests skip on a fresh clone"; \
  }();                                                                          \
  if (::testing::Test::IsSkipped()) return;                                     \
  const std::filesystem::path sharedPath = ::mvw::test::sharedDataRoot() / (relative)
