// The key file rules (messages/bus/auth_key.h): owner-only, 32 bytes or more, errors that
// name the file and say how to fix it.
#include "messages/bus/auth_key.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

namespace h4::bus {
namespace {

namespace fs = std::filesystem;

class AuthKeyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / fmt::format("h4_auth_key_{}", ::getpid());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, size_t size, mode_t mode) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << std::string(size, 'k');
    ::chmod(path.c_str(), mode);
    return path;
  }

  static std::string ErrorOf(const std::string& path) {
    try {
      ReadAuthKeyFile(path);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(AuthKeyTest, ReadsAnOwnerOnlyKeyWhole) {
  const std::string path = Write("key", 32, 0600);
  const AuthKey key = ReadAuthKeyFile(path);
  EXPECT_EQ(key.bytes, std::vector<uint8_t>(32, 'k'));
  EXPECT_EQ(key.source, path);
  EXPECT_EQ(ReadAuthKeyFile(Write("read_only", 64, 0400)).bytes.size(), 64u);
}

TEST_F(AuthKeyTest, RefusesAKeyGroupOrOthersCanReadOrWrite) {
  for (mode_t mode : {0644, 0640, 0604, 0620, 0602}) {
    const std::string path = Write("key", 32, mode);
    const std::string error = ErrorOf(path);
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_NE(error.find("chmod 600"), std::string::npos) << error;
  }
}

TEST_F(AuthKeyTest, RefusesAShortKeyAndSaysHowToMakeOne) {
  const std::string path = Write("short", 31, 0600);
  const std::string error = ErrorOf(path);
  EXPECT_NE(error.find(path + ": auth key: 31 bytes"), std::string::npos) << error;
  EXPECT_NE(error.find("head -c 32 /dev/urandom"), std::string::npos) << error;
  EXPECT_NE(ErrorOf(Write("empty", 0, 0600)), "");
}

TEST_F(AuthKeyTest, RefusesAMissingFileAndADirectoryNamingThem) {
  const std::string missing = (dir_ / "missing").string();
  EXPECT_NE(ErrorOf(missing).find(missing + ": auth key: cannot open"), std::string::npos);
  fs::create_directories(dir_ / "folder");
  ::chmod((dir_ / "folder").c_str(), 0700);
  EXPECT_NE(ErrorOf((dir_ / "folder").string()).find("not a regular file"), std::string::npos);
}

// issue 27 point 6: a FIFO blocked in open() until a writer came, before the check that
// refuses it. The read runs aside, so that a regression fails here instead of hanging.
TEST_F(AuthKeyTest, RefusesAFifoWithoutWaitingForAWriter) {
  const std::string fifo = (dir_ / "fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  std::future<std::string> error = std::async(std::launch::async, [&] { return ErrorOf(fifo); });
  if (error.wait_for(std::chrono::seconds(5)) != std::future_status::ready) {
    // Unblock the reader (a writer opens the other end), then fail.
    const int writer = ::open(fifo.c_str(), O_WRONLY);
    if (writer >= 0) ::close(writer);
    FAIL() << "reading a FIFO as a key still waits in open() for a writer";
  }
  const std::string text = error.get();
  EXPECT_NE(text.find(fifo + ": auth key: not a regular file"), std::string::npos) << text;
}

}  // namespace
}  // namespace h4::bus
