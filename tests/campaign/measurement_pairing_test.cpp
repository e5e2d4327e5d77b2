// The campaign's message checks and pairing rule (host/campaign/measurement_pairing.h).
#include "host/campaign/measurement_pairing.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace h4::host {
namespace {

h4msgs::board_pose_t GoodBoardPose() {
  h4msgs::board_pose_t m{};
  m.utime = 1'700'000'000'000'000;
  m.pose_id = 7;
  m.translation[0] = 0.01;
  m.translation[1] = -0.02;
  m.translation[2] = 0.55;
  m.quaternion[0] = std::cos(0.1);
  m.quaternion[3] = std::sin(0.1);
  for (int i = 0; i < 3; ++i) m.covariance[i * 7] = 4e-8;    // (0.2 mm)^2
  for (int i = 3; i < 6; ++i) m.covariance[i * 7] = 2.7e-7;  // (0.03 deg)^2
  m.status = h4msgs::board_pose_t::STATUS_OK;
  return m;
}

JointReading Reading(int64_t utime, int64_t pose_id, bool settled, double q1) {
  JointReading r;
  r.utime = utime;
  r.pose_id = pose_id;
  r.settled = settled;
  r.q = {q1, 0.1, 0.2, 0.3};
  return r;
}

TEST(CheckBoardPoseTest, AcceptsAPlausibleMeasurement) {
  std::string why;
  EXPECT_EQ(CheckBoardPose(GoodBoardPose(), &why), MessageProblem::kNone) << why;
}

TEST(CheckBoardPoseTest, RejectsEachImpossibleValueWithAReason) {
  // A good measurement spoilt in one value, and what the reason must say.
  const std::vector<std::pair<std::function<void(h4msgs::board_pose_t&)>, std::string>> cases = {
      {[](auto& m) { m.translation[1] = std::numeric_limits<double>::quiet_NaN(); }, "non-finite"},
      {[](auto& m) { m.quaternion[0] = 2.0; }, "not unit"},
      {[](auto& m) { m.translation[2] = -0.5; }, "in front"},  // behind the camera
      {[](auto& m) { m.covariance[35] = 0.0; }, "element 5"},
  };
  for (const auto& [spoil, reason] : cases) {
    h4msgs::board_pose_t m = GoodBoardPose();
    spoil(m);
    std::string why;
    EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kImpossibleValues) << reason;
    EXPECT_NE(why.find(reason), std::string::npos) << why;
  }
}

// Issue 42: only the diagonal was checked, so a symmetric matrix that is no covariance (a
// correlation above 1 between x and y: eigenvalue 4e-8 (1 - 1.5) < 0) was recorded; and an
// asymmetric one too. A correlation within +-1 is a covariance and passes.
TEST(CheckBoardPoseTest, RejectsACovarianceThatIsNotPositiveSemiDefiniteOrNotSymmetric) {
  h4msgs::board_pose_t m = GoodBoardPose();
  m.covariance[1] = m.covariance[6] = 1.5 * 4e-8;
  std::string why;
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNonPhysicalCovariance);
  EXPECT_NE(why.find("the covariance is not positive semi-definite"), std::string::npos) << why;
  m.covariance[1] = m.covariance[6] = 0.5 * 4e-8;
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNone) << why;
  m.covariance[6] = -0.5 * 4e-8;
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNonPhysicalCovariance);
  EXPECT_NE(why.find("the covariance is not symmetric"), std::string::npos) << why;
}

TEST(CheckJointStateTest, RejectsAWrongJointCountAndNonFinitePositions) {
  h4msgs::joint_state_t m{};
  m.utime = 10;
  m.joint_count = 3;
  m.position = {0.0, 0.0, 0.0};
  JointReading r;
  std::string why;
  EXPECT_EQ(CheckJointState(m, &r, &why), MessageProblem::kWrongJointCount);
  m.joint_count = 4;
  m.position = {0.0, std::numeric_limits<double>::infinity(), 0.0, 0.0};
  EXPECT_EQ(CheckJointState(m, &r, &why), MessageProblem::kImpossibleValues);
  m.position = {0.1, 0.2, 0.3, 0.4};
  m.pose_id = 5;
  m.settled = true;
  ASSERT_EQ(CheckJointState(m, &r, &why), MessageProblem::kNone);
  EXPECT_EQ(r.q[3], 0.4);
  EXPECT_EQ(r.pose_id, 5);
  EXPECT_TRUE(r.settled);
}

// Issue 42, defect 4: 7 rad and 1e300 rad passed (only NaN was refused) and made the
// dataset unreadable by its own reader; the bound is the reader's (kMaxJointReading).
TEST(CheckJointStateTest, RefusesAReadingTheDatasetReaderWouldRefuse) {
  h4msgs::joint_state_t m{};
  m.utime = 10;
  m.joint_count = 4;
  JointReading r;
  for (const double q : {7.0, -7.0, 1e300, kMaxJointReading * (1.0 + 1e-12)}) {
    m.position = {0.1, 0.2, q, 0.4};
    std::string why;
    EXPECT_EQ(CheckJointState(m, &r, &why), MessageProblem::kImpossibleValues) << q;
    EXPECT_NE(why.find("q3"), std::string::npos) << why;
  }
  m.position = {0.1, 0.2, kMaxJointReading, -kMaxJointReading};
  std::string why;
  EXPECT_EQ(CheckJointState(m, &r, &why), MessageProblem::kNone) << why;
}

TEST(JointHistoryTest, FindsTheNearestSettledReadingOfThePoseWithinTolerance) {
  JointHistory history;
  history.Add(Reading(1000, 3, true, 0.30));
  history.Add(Reading(2000, 4, false, 0.40));  // moving: never paired
  history.Add(Reading(3000, 4, true, 0.41));
  history.Add(Reading(4000, 4, true, 0.42));
  history.Add(Reading(5000, 5, true, 0.50));  // another pose

  const auto paired = history.FindSettled(4, 3900, 500);
  ASSERT_TRUE(paired);
  EXPECT_EQ(paired->q[0], 0.42);
  EXPECT_FALSE(history.FindSettled(4, 2000, 500)) << "the settled readings are 1000 us away";
  EXPECT_FALSE(history.FindSettled(6, 4000, 10'000));
  // Without a pose id (a robot moved by hand) any settled reading in time pairs.
  const auto by_time = history.FindSettled(std::nullopt, 4900, 500);
  ASSERT_TRUE(by_time);
  EXPECT_EQ(by_time->q[0], 0.50);
}

TEST(JointHistoryTest, KeepsOnlyTheNewestReadings) {
  JointHistory history(3);
  for (int i = 0; i < 5; ++i) history.Add(Reading(1000 * (i + 1), 1, true, 0.1 * i));
  EXPECT_FALSE(history.FindSettled(1, 1000, 10)) << "the oldest readings were dropped";
  ASSERT_TRUE(history.Latest());
  EXPECT_EQ(history.Latest()->utime, 5000);
}

TEST(JointHistoryTest, AFloodOfOtherReadingsDoesNotPushOutATrackedPosesSettledReadings) {
  JointHistory history;  // default capacities, as the campaign uses them
  history.Track(5);
  for (int i = 0; i < 10; ++i) history.Add(Reading(1'000'000 + 10'000 * i, 5, true, 0.5));
  // 60k plausible readings from another publisher: settled, another pose id, same times.
  for (int i = 0; i < 60'000; ++i) history.Add(Reading(1'000'000 + i, 77, true, 0.9));
  const auto paired = history.FindSettled(5, 1'050'000, 200'000);
  ASSERT_TRUE(paired);
  EXPECT_EQ(paired->q[0], 0.5);
  EXPECT_EQ(paired->utime, 1'050'000);
  ASSERT_TRUE(history.Latest());
  EXPECT_EQ(history.Latest()->pose_id, 77);
  // Once forgotten (recorded), the pose falls back to the shared history, long flooded.
  history.Forget(5);
  EXPECT_FALSE(history.FindSettled(5, 1'050'000, 200'000));
}

TEST(CheckBoardPoseTest, RefusesStandardDeviationsNoCameraMeasures) {
  std::string why;
  h4msgs::board_pose_t m = GoodBoardPose();
  for (int i = 0; i < 6; ++i) m.covariance[i * 7] = 1e-320;  // sigma ~1e-160, subnormal variance
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNonPhysicalCovariance);
  EXPECT_NE(why.find("element 0"), std::string::npos) << why;

  m = GoodBoardPose();
  m.covariance[28] = 1e-26;  // rotation sigma 1e-13 rad
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNonPhysicalCovariance);
  EXPECT_NE(why.find("element 4"), std::string::npos) << why;

  m = GoodBoardPose();
  m.covariance[14] = 4.0;  // 2 m
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNonPhysicalCovariance);

  m = GoodBoardPose();
  for (int i = 0; i < 6; ++i) m.covariance[i * 7] = 1e-16;  // 10 nm, 10 nrad: still accepted
  EXPECT_EQ(CheckBoardPose(m, &why), MessageProblem::kNone) << why;
}

TEST(MakeDatasetRowTest, TakesTimeAndPoseFromTheCameraAndJointsFromTheEncoders) {
  const h4msgs::board_pose_t m = GoodBoardPose();
  const DatasetRow row = MakeDatasetRow(m, Reading(m.utime + 3000, 7, true, 0.7));
  EXPECT_EQ(row.pose_id, 7);
  EXPECT_EQ(row.utime, m.utime);
  EXPECT_EQ(row.q[0], 0.7);
  EXPECT_NEAR(row.X_CT.translation().z(), 0.55, 1e-15);
  EXPECT_NEAR(row.X_CT.quaternion_wxyz()[3], std::sin(0.1), 1e-12);
  ASSERT_TRUE(row.sigma_t && row.sigma_r);
  EXPECT_NEAR(*row.sigma_t, 2e-4, 1e-12);
  EXPECT_NEAR(*row.sigma_r, std::sqrt(2.7e-7), 1e-12);
}

// The host names a received status with the camera's words; a number no camera sends is
// named as such, not mistaken for one.
TEST(BoardPoseStatusName, NamesEachWireStatusAndAnUnknownNumber) {
  EXPECT_EQ(BoardPoseStatusName(h4msgs::board_pose_t::STATUS_OK), "ok");
  EXPECT_EQ(BoardPoseStatusName(h4msgs::board_pose_t::STATUS_NO_BOARD), "no board");
  EXPECT_EQ(BoardPoseStatusName(h4msgs::board_pose_t::STATUS_MOVED), "moved");
  EXPECT_EQ(BoardPoseStatusName(h4msgs::board_pose_t::STATUS_PARTIAL), "partial");
  EXPECT_EQ(BoardPoseStatusName(h4msgs::board_pose_t::STATUS_CAMERA_ERROR), "camera error");
  EXPECT_EQ(BoardPoseStatusName(5), "unknown status 5");
  EXPECT_EQ(BoardPoseStatusName(-1), "unknown status -1");
}

}  // namespace
}  // namespace h4::host
