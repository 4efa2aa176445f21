#pragma once
// Shared by the DDS integration tests: where the executables are, a fresh folder per test, and
// readers for what `skyfuse run` writes.

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "support/process.hpp"

namespace skyfuse::test {

inline std::string bin(const std::string& name) {
  return std::string(SKYFUSE_BIN_DIR) + "/" + name;
}

/// A clean folder named after the running test.
inline std::filesystem::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  const auto dir = std::filesystem::path(SKYFUSE_TEST_WORK_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

using StateRow = std::array<double, 9>;
/// tracks.csv as (step, source) -> state; %.17g in the file makes the values exact.
std::map<std::pair<int, int>, StateRow> read_tracks(const std::filesystem::path& csv);

}  // namespace skyfuse::test
