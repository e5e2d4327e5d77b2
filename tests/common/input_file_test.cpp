// Reading input files (common/formats/input_file.h): every data file reader goes through it,
// so a FIFO, a device or a file beyond the limit is refused at once, naming the file, instead
// of hanging or filling the memory (issue 42 point 3).
#include "common/formats/input_file.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/formats/corners_csv.h"
#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "tests/support/test_dir.h"

namespace h4 {
namespace {

namespace fs = std::filesystem;

/// ReadTextFile(path)'s error, run aside: a regression that waits on a FIFO fails here after
/// 5 s (a writer is then opened to release it) instead of hanging the test.
std::string ReadError(const std::string& path) {
  std::future<std::string> error = std::async(std::launch::async, [path] {
    try {
      ReadTextFile(path);
      return std::string("read without an error");
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
  });
  if (error.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
    const int writer = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0) ::close(writer);
    ADD_FAILURE() << path << ": the read still waits for a writer";
  }
  return error.get();
}

// `--corners`, `--data`, `--robot` naming a FIFO hung forever: every reader's ReadTextFile.
TEST(InputFile, AFifoIsRefusedWithoutWaitingForAWriter) {
  const fs::path dir = FreshTestDir("h4_input_file_");
  const std::string fifo = (dir / "corners.csv").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string error = ReadError(fifo);
  EXPECT_NE(error.find(fifo + ": not a regular file (a FIFO)"), std::string::npos) << error;
  fs::remove_all(dir);
}

// /dev/zero was read until the memory ran out; a device is refused before any read (shown
// on /dev/null, which a regression reads as an empty file instead of exhausting memory).
TEST(InputFile, ADeviceOrADirectoryIsRefused) {
  EXPECT_NE(ReadError("/dev/null").find("/dev/null: not a regular file (a character device)"),
            std::string::npos);
  EXPECT_NE(ReadError("/").find("/: not a regular file (a directory)"), std::string::npos);
  EXPECT_NE(ReadError("/nonexistent/h4/x.csv").find("cannot open: No such file"),
            std::string::npos);
  // The corners reader, one of those every command uses, says the same.
  try {
    ReadCornersCsv("/dev/null");
    ADD_FAILURE() << "read /dev/null as corners";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

TEST(InputFile, AFileOverTheLimitIsRefusedBeforeItIsRead) {
  const fs::path dir = FreshTestDir("h4_input_file_");
  const std::string path = (dir / "big.csv").string();
  std::ofstream(path) << std::string(1000, 'x');
  InputFile file(path);
  ASSERT_TRUE(file.ok()) << file.error();
  EXPECT_EQ(file.size(), 1000);
  std::string bytes;
  EXPECT_FALSE(file.ReadAll(999, &bytes));
  EXPECT_NE(file.error().find("1000 bytes; a file read here holds at most 999"),
            std::string::npos)
      << file.error();
  EXPECT_THROW(ReadDataFile(path, 999), FormatError);
  EXPECT_EQ(ReadDataFile(path, 1000).size(), 1000u);
  // A sparse file the size of the data limit plus one: refused from its size alone.
  const std::string sparse = (dir / "sparse.csv").string();
  std::ofstream(sparse).close();
  fs::resize_file(sparse, kMaxDataFileBytes + 1);
  try {
    ReadTextFile(sparse);
    ADD_FAILURE() << "read a file over the limit";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("{} bytes", kMaxDataFileBytes + 1)),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace h4
