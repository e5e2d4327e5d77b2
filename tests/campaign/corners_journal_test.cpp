// Durable, resumable appends of the campaign's board corners (host/campaign/corners_journal.h,
// common/formats/README.md#board-corners-csv).
#include "host/campaign/corners_journal.h"

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "tests/support/test_dir.h"

namespace h4::host {
namespace {

namespace fs = std::filesystem;

std::vector<CornerObservation> CornersOfPose(int64_t pose_id, int count = 3) {
  std::vector<CornerObservation> corners;
  for (int k = 0; k < count; ++k) {
    corners.push_back({pose_id, 2, 8 + k, 10.5 * static_cast<double>(pose_id) + k, 20.25, 0.04});
  }
  return corners;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

class CornersJournalTest : public TestWithDatasetFile {
 protected:
  CornersJournalTest() : TestWithDatasetFile("h4_corners_journal_") {}
  void SetUp() override {
    TestWithDatasetFile::SetUp();
    corners_path_ = CornersPathBeside(path_);
  }
  std::string corners_path_;
};

TEST(CornersPathBeside, IsTheDatasetStemWithCornersCsvInItsDirectory) {
  EXPECT_EQ(CornersPathBeside("runs/day1.csv"), "runs/day1.corners.csv");
  EXPECT_EQ(CornersPathBeside("data.csv"), "data.corners.csv");
  EXPECT_EQ(CornersPathBeside("/tmp/a.b/set"), "/tmp/a.b/set.corners.csv");
}

TEST_F(CornersJournalTest, WritesPosesThatReadBackAndResumesWithThem) {
  {
    CornersJournal journal(corners_path_);
    journal.Append(CornersOfPose(1));
    journal.Append(CornersOfPose(4));
    // Durable: on disk before the journal is closed.
    EXPECT_EQ(ReadCornersCsv(corners_path_).size(), 6u);
    EXPECT_TRUE(journal.Contains(4));
    EXPECT_THROW(journal.Append(CornersOfPose(4)), std::invalid_argument);
  }
  CornersJournal resumed(corners_path_);
  EXPECT_TRUE(resumed.Contains(1));
  EXPECT_TRUE(resumed.Contains(4));
  EXPECT_EQ(resumed.pose_count(), 2u);
  resumed.Append(CornersOfPose(5));
  const std::vector<CornerObservation> back = ReadCornersCsv(corners_path_);
  ASSERT_EQ(back.size(), 9u);
  EXPECT_EQ(back[8].pose_id, 5);
  EXPECT_EQ(back[8].u, 52.5 + 2);
  EXPECT_EQ(ReadTextFile(corners_path_).substr(0, 37), "pose_id,tag_id,corner,u,v,sigma_px\n1,");
}

TEST_F(CornersJournalTest, ResumesAFileWithCrlfLineEndsOrAByteOrderMark) {
  { CornersJournal(corners_path_).Append(CornersOfPose(1)); }
  const std::string lf = ReadTextFile(corners_path_);
  std::string crlf;
  for (char c : lf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& text : {crlf, "\xEF\xBB\xBF" + lf}) {
    std::ofstream(corners_path_, std::ios::binary | std::ios::trunc) << text;
    CornersJournal resumed(corners_path_);
    EXPECT_TRUE(resumed.Contains(1));
    resumed.Append(CornersOfPose(2));
    EXPECT_EQ(ReadCornersCsv(corners_path_).size(), 6u);
  }
}

TEST_F(CornersJournalTest, RefusesMixedPosesAndAnEmptyList) {
  CornersJournal journal(corners_path_);
  std::vector<CornerObservation> mixed = CornersOfPose(1);
  mixed[2].pose_id = 2;
  EXPECT_THROW(journal.Append(mixed), std::invalid_argument);
  EXPECT_THROW(journal.Append({}), std::invalid_argument);
  // Parsed, not read with ReadCornersCsv: a command refuses a corners file with no row.
  EXPECT_TRUE(ParseCornersCsv(ReadTextFile(corners_path_), corners_path_).empty())
      << "nothing of a refused append";
}

// A crash inside a pose's write leaves a cut last line: that pose's rows all go, the whole
// poses before it stay.
TEST_F(CornersJournalTest, DropsThePoseACrashCut) {
  {
    CornersJournal journal(corners_path_);
    journal.Append(CornersOfPose(1));
  }
  const std::string whole = ReadTextFile(corners_path_);
  WriteText(corners_path_, whole + "2,2,8,21,20.25,0.04\n2,2,9,22,20.2");
  {
    CornersJournal journal(corners_path_);
    EXPECT_TRUE(journal.Contains(1));
    EXPECT_FALSE(journal.Contains(2));
    journal.Append(CornersOfPose(2));
  }
  const std::vector<CornerObservation> back = ReadCornersCsv(corners_path_);
  ASSERT_EQ(back.size(), 6u);
  EXPECT_EQ(back[3].pose_id, 2);
  EXPECT_EQ(back[3].u, 21.0);
  // A cut inside the pose id cannot tell its pose: the last whole one goes too.
  WriteText(corners_path_, whole + "1");
  CornersJournal journal(corners_path_);
  EXPECT_FALSE(journal.Contains(1));
  EXPECT_EQ(ReadTextFile(corners_path_), "pose_id,tag_id,corner,u,v,sigma_px\n");
}

DatasetRow RowOfPose(int64_t id) {
  DatasetRow row;
  row.pose_id = id;
  row.utime = 1'700'000'000'000'000 + id;
  row.q = {0.01 * static_cast<double>(id), 0.2, 0.3, 0.4};
  row.X_CT = RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.01, 0.02, 0.5),
                                                Eigen::Vector3d(0.1, -0.2, 0.3));
  row.sigma_t = 2e-4;
  row.sigma_r = 5e-4;
  return row;
}

// Issue 42, defect 6: a crash between a pose's row and its corners lost the corners for
// good ("12 of 12 planned poses, corners of 9 poses"). The rows at the end without corners
// are cut from the dataset so that the resumed campaign measures them again.
TEST_F(CornersJournalTest, RowsWhoseCornersACrashLostAreMeasuredAgain) {
  {
    DatasetJournal dataset(path_);
    CornersJournal corners(corners_path_);
    for (int64_t id = 1; id <= 4; ++id) dataset.Append(RowOfPose(id));
    for (int64_t id = 1; id <= 2; ++id) corners.Append(CornersOfPose(id));
  }  // killed before the corners of 3 and 4
  DatasetJournal dataset(path_);
  CornersJournal corners(corners_path_);
  EXPECT_EQ(ReconcileWithDataset(dataset, corners), (std::vector<int64_t>{3, 4}));
  EXPECT_FALSE(dataset.Contains(3));
  EXPECT_FALSE(dataset.Contains(4));
  ASSERT_EQ(ReadDatasetCsv(path_).size(), 2u);
  dataset.Append(RowOfPose(3));
  corners.Append(CornersOfPose(3));
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 3u);
  EXPECT_TRUE(ReconcileWithDataset(dataset, corners).empty());
}

// Rows of a camera that sends no corners are kept: nothing says they lost any.
TEST_F(CornersJournalTest, RowsOfACameraWithoutCornersAreKept) {
  DatasetJournal dataset(path_);
  CornersJournal corners(corners_path_);
  dataset.Append(RowOfPose(1));
  dataset.Append(RowOfPose(2));
  EXPECT_TRUE(ReconcileWithDataset(dataset, corners).empty());
  EXPECT_EQ(dataset.rows().size(), 2u);
}

// Issue 42, defect 10: a new campaign beside an old STEM.corners.csv kept the old corners
// for the new poses (identify --corners then fitted stale pixels). Corners of poses the
// dataset has no row of are refused, naming them, and neither file changes.
TEST_F(CornersJournalTest, AnotherCampaignsCornersAreRefused) {
  {
    CornersJournal old(corners_path_);
    for (int64_t id = 1; id <= 3; ++id) old.Append(CornersOfPose(id));
  }
  const std::string before = ReadTextFile(corners_path_);
  DatasetJournal dataset(path_);
  CornersJournal corners(corners_path_);
  try {
    ReconcileWithDataset(dataset, corners);
    ADD_FAILURE() << "the old corners were accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("pose 1, 2, 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("another campaign's corners"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadTextFile(corners_path_), before);
  EXPECT_TRUE(dataset.rows().empty());
}

TEST_F(CornersJournalTest, RefusesAFileWithOtherColumnsOrMalformedRows) {
  WriteText(corners_path_, "pose_id,tag_id,corner,u,v\n1,0,0,1,1\n");
  try {
    CornersJournal journal(corners_path_);
    FAIL() << "expected a refusal";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("other columns"), std::string::npos) << e.what();
  }
  WriteText(corners_path_, "pose_id,tag_id,corner,u,v,sigma_px\n1,0,0,1,x,\n");
  EXPECT_THROW(CornersJournal journal(corners_path_), FormatError);
}

TEST_F(CornersJournalTest, AFailedFsyncCutsThePoseOff) {
  JournalFileOps ops;
  bool fail = false;
  ops.fsync = [&fail](int fd) {
    if (!fail) return ::fsync(fd);
    errno = EIO;
    return -1;
  };
  CornersJournal journal(corners_path_, ops);
  journal.Append(CornersOfPose(1));
  fail = true;
  EXPECT_THROW(journal.Append(CornersOfPose(2)), std::runtime_error);
  EXPECT_FALSE(journal.Contains(2));
  EXPECT_EQ(ReadCornersCsv(corners_path_).size(), 3u);
}

}  // namespace
}  // namespace h4::host
