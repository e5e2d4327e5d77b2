// Test helpers: a fresh, empty directory for the running test, named after it so that tests
// run in parallel (one process each under ctest) never share files; a fixture writing a
// dataset CSV in one.
#pragma once

#include <filesystem>
#include <string>
#include <utility>

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

/// A test writing a dataset CSV: `path_` in its own fresh directory `dir_` (FreshTestDir with
/// `prefix`), removed after the test.
class TestWithDatasetFile : public ::testing::Test {
 protected:
  explicit TestWithDatasetFile(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    dir_ = FreshTestDir(prefix_);
    path_ = (dir_ / "dataset.csv").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  std::string path_;

 private:
  std::string prefix_;
};

}  // namespace h4
