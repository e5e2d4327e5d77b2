// Atomic file replacement and the same-file check (data loss): a failed write
// keeps the previous file whole and leaves no temporary behind; an output that is one of
// the inputs is refused, by path, through "./" and through a hard or symbolic link.
#include "common/formats/file_output.h"

#include <csignal>
#include <filesystem>
#include <stdexcept>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include "common/formats/csv_table.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

namespace fs = std::filesystem;

int CountTemporaries(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) ++n;
  }
  return n;
}

// While alive, writes beyond `bytes` fail with EFBIG (SIGXFSZ ignored): a failing disk
// that root's permissions cannot fake.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = SIG_DFL;
};

TEST(WriteFileAtomically, ReplacesTheFileAndLeavesNoTemporary) {
  const std::string path = TempPath("out.txt");
  WriteFileAtomically(path, "first\n");
  WriteFileAtomically(path, "second\n");
  EXPECT_EQ(ReadTextFile(path), "second\n");
  EXPECT_EQ(CountTemporaries(fs::path(path).parent_path()), 0);
}

TEST(WriteFileAtomically, AFailedWriteKeepsThePreviousFileWhole) {
  const std::string path = TempPath("result.json");
  const std::string previous(3000, 'p');
  WriteFileAtomically(path, previous);
  // Nothing is printed while the limit holds (the test log may be a file itself).
  bool atomic_threw = false;
  bool text_threw = false;
  {
    const FileSizeLimit limit(1024);
    try {
      WriteFileAtomically(path, std::string(1 << 20, 'n'));
    } catch (const std::runtime_error&) {
      atomic_threw = true;
    }
    try {
      WriteTextFile(path, std::string(1 << 20, 'n'));  // the writer every format uses
    } catch (const std::runtime_error&) {
      text_threw = true;
    }
  }
  EXPECT_TRUE(atomic_threw);
  EXPECT_TRUE(text_threw);
  EXPECT_EQ(ReadTextFile(path), previous);
  EXPECT_EQ(CountTemporaries(fs::path(path).parent_path()), 0);
}

TEST(WriteFileAtomically, ThroughALinkReplacesItsTargetAndADeviceIsWrittenInPlace) {
  const std::string target = TempPath("target.yaml");
  const std::string link = TempPath("link.yaml");
  WriteFileAtomically(target, "old\n");
  fs::remove(link);
  fs::create_symlink(target, link);
  WriteFileAtomically(link, "new\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(ReadTextFile(target), "new\n");
  // Renaming over /dev/null would replace the device with a file.
  WriteFileAtomically("/dev/null", "discarded\n");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(CountTemporaries("/dev"), 0);
}

TEST(WriteFileAtomically, AMissingFolderIsNamed) {
  const std::string path = TempPath("absent") + "/out.txt";
  try {
    WriteFileAtomically(path, "x");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(IsSameFile, RecognisesOneFileUnderSeveralNames) {
  const std::string path = TempPath("data.csv");
  WriteFileAtomically(path, "a\n");
  const fs::path dir = fs::path(path).parent_path();
  const std::string dotted = (dir / "." / fs::path(path).filename()).string();
  const std::string hard = path + ".hard";
  const std::string soft = path + ".soft";
  fs::remove(hard);
  fs::remove(soft);
  fs::create_hard_link(path, hard);
  fs::create_symlink(path, soft);
  EXPECT_TRUE(IsSameFile(path, path));
  EXPECT_TRUE(IsSameFile(path, dotted));
  EXPECT_TRUE(IsSameFile(path, hard));
  EXPECT_TRUE(IsSameFile(soft, path));
  const std::string other = TempPath("other.csv");
  WriteFileAtomically(other, "a\n");
  EXPECT_FALSE(IsSameFile(path, other));
  // Not yet existing: compared by canonical path.
  const std::string absent = TempPath("absent.csv");
  EXPECT_TRUE(IsSameFile(absent, (dir / "." / fs::path(absent).filename()).string()));
  EXPECT_FALSE(IsSameFile(absent, path));
}

TEST(RequireOutputIsNotAnInput, NamesBothOptions) {
  const std::string data = TempPath("data.csv");
  WriteFileAtomically(data, "a\n");
  try {
    RequireOutputIsNotAnInput({"--out", data}, {{"--robot", ""}, {"--data", data}});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--out " + data + " is the same file as --data " + data), std::string::npos)
        << what;
  }
  EXPECT_NO_THROW(RequireOutputIsNotAnInput({"--out", TempPath("r.json")}, {{"--data", data}}));
  EXPECT_NO_THROW(RequireOutputIsNotAnInput({"--out", ""}, {{"--data", data}}));
}

}  // namespace
}  // namespace h4
