// Durable, resumable appends of the campaign's dataset (host/campaign/dataset_journal.h).
#include "host/campaign/dataset_journal.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "common/formats/format_error.h"

namespace h4::host {
namespace {

namespace fs = std::filesystem;

DatasetRow Row(int64_t id) {
  DatasetRow row;
  row.pose_id = id;
  row.utime = 1'700'000'000'000'000 + id;
  row.q = {0.1 * static_cast<double>(id), 0.2, 0.3, 0.4};
  row.X_CT = RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.01, 0.02, 0.5 + 0.01 * id),
                                                Eigen::Vector3d(0.1, -0.2, 0.3));
  row.sigma_t = 2e-4;
  row.sigma_r = 5e-4;
  return row;
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class DatasetJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("h4_journal_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "dataset.csv").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string path_;
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
    EXPECT_EQ(on_disk[1].q[0], 0.2);
    ASSERT_TRUE(on_disk[1].sigma_t);
    EXPECT_EQ(*on_disk[1].sigma_t, 2e-4);
  }
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
  const std::string whole = Slurp(path_);
  std::ofstream(path_, std::ios::app) << "3,1700000000000003,0.3,0.2";  // no newline
  DatasetJournal resumed(path_);
  EXPECT_EQ(resumed.resumed_count(), 2u);
  EXPECT_FALSE(resumed.Contains(3));
  EXPECT_EQ(Slurp(path_), whole) << "the cut line is removed from the file";
  resumed.Append(Row(3));
  EXPECT_EQ(ReadDatasetCsv(path_).size(), 3u);
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

}  // namespace
}  // namespace h4::host
