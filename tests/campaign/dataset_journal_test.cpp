// Durable, resumable appends of the campaign's dataset (host/campaign/dataset_journal.h).
#include "host/campaign/dataset_journal.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "tests/support/test_dir.h"

namespace h4::host {
namespace {

namespace fs = std::filesystem;

DatasetRow Row(int64_t id) {
  DatasetRow row;
  row.pose_id = id;
  row.utime = 1'700'000'000'000'000 + id;
  // Every value varies with the id but stays within the reader's bounds (a joint within a
  // turn, a translation within 10 m) however many rows a fast machine writes before a kill:
  // one CI machine wrote over 950.
  const double step = static_cast<double>(id % 600);
  row.q = {0.01 * step, 0.2, 0.3, 0.4};
  row.X_CT = RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.01, 0.02, 0.5 + 0.01 * step),
                                                Eigen::Vector3d(0.1, -0.2, 0.3));
  row.sigma_t = 2e-4;
  row.sigma_r = 5e-4;
  return row;
}

class DatasetJournalTest : public TestWithDatasetFile {
 protected:
  DatasetJournalTest() : TestWithDatasetFile("h4_journal_") {}
};

TEST_F(DatasetJournalTest, WritesRowsThatReadBackAsADataset) {
  {
    DatasetJournal journal(path_);
    journal.Append(Row(1));
    journal.Append(Row(2));
    // Durable: already on disk before the journal is closed.
    const std::vector<DatasetRow> on_disk = ReadDatasetCsv(path_);
    ASSERT_EQ(on_disk.size(), 2u);
    EXPECT_EQ(on_disk[1].pose_id, 2);
    EXPECT_EQ(on_disk[1].q[0], 0.02);
    ASSERT_TRUE(on_disk[1].sigma_t);
    EXPECT_EQ(*on_disk[1].sigma_t, 2e-4);
  }
}

// Issue 42, defect 4: a row its own reader refuses is never written (the file stays
// readable, the pose is not counted as recorded).
TEST_F(DatasetJournalTest, RefusesARowItsReaderWouldRefuse) {
  DatasetJournal journal(path_);
  journal.Append(Row(1));
  DatasetRow bad = Row(2);
  bad.q[1] = 7.0;
  EXPECT_THROW(journal.Append(bad), std::invalid_argument);
  EXPECT_FALSE(journal.Contains(2));
  const std::vector<DatasetRow> on_disk = ReadDatasetCsv(path_);
  ASSERT_EQ(on_disk.size(), 1u);
  journal.Append(Row(2));
}

TEST_F(DatasetJournalTest, ResumesWithThePosesAlreadyRecorded) {
  {
    DatasetJournal journal(path_);
    journal.Append(Row(1));
    journal.Append(Row(5));
  }
  DatasetJournal resumed(path_);
  EXPECT_EQ(resumed.resumed_count(), 2u);
  EXPECT_TRUE(resumed.Contains(5));
  EXPECT_FALSE(resumed.Contains(2));
  resumed.Append(Row(2));
  EXPECT_THROW(resumed.Append(Row(5)), std::invalid_argument);
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 3u);
}

TEST_F(DatasetJournalTest, DropsALastLineCutByACrash) {
  {
    DatasetJournal journal(path_);
    journal.Append(Row(1));
    journal.Append(Row(2));
  }
  const std::string whole = ReadTextFile(path_);
  std::ofstream(path_, std::ios::app) << "3,1700000000000003,0.3,0.2";  // no newline
  DatasetJournal resumed(path_);
  EXPECT_EQ(resumed.resumed_count(), 2u);
  EXPECT_FALSE(resumed.Contains(3));
  EXPECT_EQ(ReadTextFile(path_), whole) << "the cut line is removed from the file";
  resumed.Append(Row(3));
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 3u);
}

// issue 27 point 13: a dataset saved with CRLF line ends or a byte order mark (which the
// readers take) was refused on resume, "exists with other columns", quoting two headers
// that print the same.
TEST_F(DatasetJournalTest, ResumesAFileWithCrlfLineEndsOrAByteOrderMark) {
  {
    DatasetJournal journal(path_);
    journal.Append(Row(1));
  }
  const std::string lf = ReadTextFile(path_);
  std::string crlf;
  for (char c : lf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& text : {crlf, "\xEF\xBB\xBF" + lf, "\xEF\xBB\xBF" + crlf}) {
    std::ofstream(path_, std::ios::binary | std::ios::trunc) << text;
    DatasetJournal resumed(path_);
    EXPECT_EQ(resumed.resumed_count(), 1u);
    EXPECT_TRUE(resumed.Contains(1));
    resumed.Append(Row(2));
    EXPECT_EQ(ReadDatasetCsv(path_).size(), 2u);
  }
}

TEST_F(DatasetJournalTest, RefusesAFileWithOtherColumns) {
  std::ofstream(path_) << "pose_id,utime,q1,q2,q3,q4,x,y,z,qw,qx,qy,qz\n";
  try {
    DatasetJournal journal(path_);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path_), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("other columns"), std::string::npos) << e.what();
  }
}

TEST_F(DatasetJournalTest, RefusesAMalformedExistingRowNamingTheLine) {
  {
    DatasetJournal journal(path_);
    journal.Append(Row(1));
  }
  std::ofstream(path_, std::ios::app) << "2,17,0.1,oops,0.3,0.4,0,0,0.5,1,0,0,0,2e-4,5e-4\n";
  try {
    DatasetJournal journal(path_);
    FAIL() << "expected a FormatError";
  } catch (const FormatError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("q2"), std::string::npos) << e.what();
  }
}

TEST_F(DatasetJournalTest, NamesTheFileWhenItCannotBeCreated) {
  const std::string bad = (dir_ / "no_such_dir" / "d.csv").string();
  try {
    DatasetJournal journal(bad);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

TEST_F(DatasetJournalTest, ASecondJournalOnTheSameFileIsRefusedNamingTheHolder) {
  DatasetJournal first(path_);
  first.Append(Row(1));
  try {
    DatasetJournal second(path_);
    FAIL() << "two campaigns on one file would interleave their rows";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path_), std::string::npos) << what;
    EXPECT_NE(what.find("another campaign is writing it"), std::string::npos) << what;
    EXPECT_NE(what.find(fmt::format("process {}", getpid())), std::string::npos) << what;
  }
  first.Append(Row(2));
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 2u) << "the refused journal touched nothing";
}

TEST_F(DatasetJournalTest, TheLockIsReleasedWithTheJournal) {
  { DatasetJournal first(path_); }
  EXPECT_NO_THROW(DatasetJournal second(path_));
}

// A disk that fills in the middle of a row (the file size limit makes write(2) fail the way
// a full disk does: a short write, then an error): the campaign gets an error naming the
// file and the reason, and the file keeps its complete rows only.
TEST_F(DatasetJournalTest, AWriteThatFailsMidRowLeavesOnlyCompleteRowsAndSaysWhy) {
  DatasetJournal journal(path_);
  journal.Append(Row(1));
  journal.Append(Row(2));
  const std::string before = ReadTextFile(path_);

  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit limited = saved;
  limited.rlim_cur = before.size() + 20;  // room for a part of the next row only
  void (*saved_handler)(int) = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
  std::string error;
  try {
    journal.Append(Row(3));
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, saved_handler);

  ASSERT_FALSE(error.empty()) << "the write cannot have succeeded";
  EXPECT_NE(error.find(path_ + ": cannot write"), std::string::npos) << error;
  EXPECT_NE(error.find("complete rows only"), std::string::npos) << error;
  EXPECT_EQ(ReadTextFile(path_), before) << "no part of row 3 may stay in the file";
  EXPECT_FALSE(journal.Contains(3));

  // Space again: the same journal goes on.
  journal.Append(Row(3));
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 3u);
}

// An fsync that fails after the row was written (EIO from the disk, injected through the
// journal's file operations): the row is not known to be on the disk, so it is cut off, the
// error names the file and fsync, and the rows flushed before stay whole.
TEST_F(DatasetJournalTest, AFailedFsyncCutsTheRowOffAndSaysWhy) {
  bool fail_fsync = false;
  int fsync_calls = 0;
  JournalFileOps ops;
  ops.fsync = [&](int fd) {
    ++fsync_calls;
    if (!fail_fsync) return ::fsync(fd);
    errno = EIO;
    return -1;
  };
  DatasetJournal journal(path_, ops);
  journal.Append(Row(1));
  journal.Append(Row(2));
  const std::string before = ReadTextFile(path_);
  const int calls_before = fsync_calls;

  fail_fsync = true;
  std::string error;
  try {
    journal.Append(Row(3));
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  fail_fsync = false;
  EXPECT_EQ(fsync_calls, calls_before + 1) << "the injected fsync is the journal's";
  ASSERT_FALSE(error.empty()) << "a failed fsync must not be taken for a durable row";
  EXPECT_NE(error.find(path_ + ": cannot flush to disk (fsync): " + std::strerror(EIO)),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("complete rows only"), std::string::npos) << error;
  EXPECT_EQ(ReadTextFile(path_), before) << "no part of row 3 may stay in the file";
  EXPECT_FALSE(journal.Contains(3));
  EXPECT_EQ(journal.rows().size(), 2u);

  // The disk back: the same journal goes on, and a resumed one reads every row once.
  journal.Append(Row(3));
  const std::vector<DatasetRow> rows = ReadDatasetCsv(path_);
  ASSERT_EQ(rows.size(), 3u);
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].pose_id, static_cast<int64_t>(i) + 1);
}

TEST_F(DatasetJournalTest, RefusesWhatIsNotARegularFile) {
  try {
    DatasetJournal journal("/dev/null");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/null: is not a regular file"), std::string::npos)
        << e.what();
  }
}

// A campaign killed (SIGKILL) at random points, 20 times, each run resuming the last: the
// file always reads back as complete rows with pose ids 1..n, each exactly once.
TEST_F(DatasetJournalTest, KilledAtRandomPointsAndResumedKeepsEveryRowExactlyOnce) {
  std::mt19937 rng(20);
  size_t rows_before = 0;
  for (int run = 0; run < 20; ++run) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      // The child appends as fast as it can until it is killed; it never returns to gtest.
      try {
        DatasetJournal journal(path_);
        for (int64_t id = static_cast<int64_t>(journal.rows().size()) + 1;; ++id) {
          journal.Append(Row(id));
        }
      } catch (...) {
      }
      _exit(1);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500 + rng() % 20000));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "run " << run << ": the child stopped by itself";

    DatasetJournal resumed(path_);  // drops a row cut by the kill, if any
    const std::vector<DatasetRow>& rows = resumed.rows();
    ASSERT_GE(rows.size(), rows_before) << "run " << run << ": rows were lost";
    for (size_t i = 0; i < rows.size(); ++i) {
      ASSERT_EQ(rows[i].pose_id, static_cast<int64_t>(i) + 1) << "run " << run;
      ASSERT_EQ(rows[i].q, Row(rows[i].pose_id).q) << "run " << run;
    }
    rows_before = rows.size();
  }
  EXPECT_GT(rows_before, 0u);
}

}  // namespace
}  // namespace h4::host
