// Test helper: a fresh, empty directory for the running test, named after it so that tests
// run in parallel (one process each under ctest) never share files.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace h4 {

/// Creates (emptied first) and returns <parent>/<prefix><test name>; the parent defaults
/// to the system's temporary directory.
inline std::filesystem::path FreshTestDir(
    const std::string& prefix,
    const std::filesystem::path& parent = std::filesystem::temp_directory_path()) {
  const std::filesystem::path dir =
      parent / (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace h4
