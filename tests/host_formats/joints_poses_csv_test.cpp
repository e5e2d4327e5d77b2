// Joints CSV, poses CSV and the fk output: known values, exact round trips, and the
// malformed inputs with their line and field.
#include <random>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/formats/joints_csv.h"
#include "host/formats/poses_csv.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

TEST(JointsCsv, ReadsKnownValues) {
  const std::vector<JointsRow> rows =
      ParseJointsCsv("q4,q3,q2,q1,pose_id\n-3.1,3.1,0.5,-0.5,12\n0,0,0,0,13\n", "j.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].pose_id, 12);
  EXPECT_EQ(rows[0].q, (std::array<double, 4>{-0.5, 0.5, 3.1, -3.1}));
  EXPECT_EQ(rows[1].pose_id, 13);
}

TEST(JointsCsv, RoundTripIsExact) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.2, 3.2);
  std::vector<JointsRow> rows;
  for (int i = 0; i < 30; ++i) rows.push_back({i - 5, {u(rng), u(rng), u(rng), u(rng)}});
  const std::string text = FormatJointsCsv(rows);
  EXPECT_EQ(text.substr(0, text.find('\n')), "pose_id,q1,q2,q3,q4");
  const std::vector<JointsRow> back = ParseJointsCsv(text, "mem");
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].pose_id, rows[i].pose_id);
    EXPECT_EQ(back[i].q, rows[i].q);
  }
  const std::string path = TempPath("joints.csv");
  WriteJointsCsv(path, rows);
  EXPECT_EQ(ReadJointsCsv(path).size(), rows.size());
}

TEST(JointsCsvErrors, NameLineAndField) {
  EXPECT_TRUE(FailsWith([] { ParseJointsCsv("pose_id,q1,q2,q4\n", "j.csv"); }, "j.csv", 1, "q3",
                        "missing column"));
  EXPECT_TRUE(FailsWith([] { ParseJointsCsv("pose_id,q1,q2,q3,q4\n1,0,0,x,0\n", "j.csv"); },
                        "j.csv", 2, "q3", "expected a number, got 'x'"));
  EXPECT_TRUE(FailsWith([] { ParseJointsCsv("pose_id,q1,q2,q3,q4\n1,0,0,0\n", "j.csv"); }, "j.csv",
                        2, "q4", "missing field"));
  EXPECT_TRUE(
      FailsWith([] { ParseJointsCsv("pose_id,q1,q2,q3,q4\n1,0,0,0,0\n\n1,0,0,0,0\n", "j.csv"); },
                "j.csv", 4, "pose_id", "duplicate pose_id 1 (first on line 2)"));
}

TEST(PosesCsv, ReadsKnownValuesAndRoundTrips) {
  const std::vector<EndEffectorPoseRow> rows =
      ParsePosesCsv("pose_id,X,Y,Z,theta\n1,0.1,-0.1,-0.45,0.349\n", "p.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].pose_id, 1);
  EXPECT_EQ(rows[0].X, 0.1);
  EXPECT_EQ(rows[0].Y, -0.1);
  EXPECT_EQ(rows[0].Z, -0.45);
  EXPECT_EQ(rows[0].theta, 0.349);
  const std::vector<EndEffectorPoseRow> more = {{2, 1.0 / 3, 2.0 / 7, -0.45, -0.2}, rows[0]};
  const std::vector<EndEffectorPoseRow> back = ParsePosesCsv(FormatPosesCsv(more), "mem");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].X, 1.0 / 3);
  EXPECT_EQ(back[0].Y, 2.0 / 7);
  EXPECT_EQ(back[1].theta, 0.349);
  const std::string path = TempPath("poses.csv");
  WritePosesCsv(path, more);
  EXPECT_EQ(ReadPosesCsv(path)[0].pose_id, 2);
}

TEST(PosesCsvErrors, NameLineAndField) {
  // Column names are case-sensitive: x is the board's, X the end-effector's.
  EXPECT_TRUE(FailsWith([] { ParsePosesCsv("pose_id,x,Y,Z,theta\n", "p.csv"); }, "p.csv", 1, "X",
                        "missing column"));
  EXPECT_TRUE(FailsWith([] { ParsePosesCsv("pose_id,X,Y,Z,theta\n1,0,0,-0.4,20deg\n", "p.csv"); },
                        "p.csv", 2, "theta", "got '20deg'"));
  EXPECT_TRUE(
      FailsWith([] { ParsePosesCsv("pose_id,X,Y,Z,theta\n1,0,0,0,0\n1,0,0,0,0\n", "p.csv"); },
                "p.csv", 3, "pose_id", "duplicate"));
}

// Regression: ik accepted theta = 20 (degrees by mistake) and positions of 1e308 m.
TEST(PosesCsvErrors, ThetaAndPositionsOutOfRange) {
  const auto parse = [](const std::string& row) {
    return [row] { ParsePosesCsv("pose_id,X,Y,Z,theta\n" + row + "\n", "p.csv"); };
  };
  EXPECT_TRUE(
      FailsWith(parse("1,0,0,-0.45,20"), "p.csv", 2, "theta", "expected |theta| <= 3.14159"));
  EXPECT_TRUE(FailsWith(parse("1,0,0,-0.45,-3.2"), "p.csv", 2, "theta", "got -3.2"));
  EXPECT_TRUE(FailsWith(parse("1,1e308,0,-0.45,0"), "p.csv", 2, "X", "expected |X| <= 10 m"));
  EXPECT_TRUE(FailsWith(parse("1,0,-11,-0.45,0"), "p.csv", 2, "Y", "10 m"));
  EXPECT_TRUE(FailsWith(parse("1,0,0,1e300,0"), "p.csv", 2, "Z", "10 m"));
  EXPECT_NO_THROW(parse("1,0.2,-0.2,-0.6,3.14159")());
}

TEST(FkCsv, RoundTripAndHeader) {
  std::vector<FkRow> rows(2);
  rows[0].pose = {5, 0.1, 0.2, -0.45, 0.3};
  rows[0].X_CT = RigidTransform(RotZ(0.3), {0.01, 0.02, 0.6});
  rows[1].pose = {6, -0.1, 0.0, -0.5, -0.3};
  const std::string text = FormatFkCsv(rows);
  EXPECT_EQ(text.substr(0, text.find('\n')), "pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy,qz");
  const std::vector<FkRow> back = ParseFkCsv(text, "mem");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].pose.pose_id, 5);
  EXPECT_EQ(back[0].pose.theta, 0.3);
  EXPECT_EQ(back[0].X_CT.translation(), rows[0].X_CT.translation());
  EXPECT_LT((back[0].X_CT.rotation() - RotZ(0.3)).cwiseAbs().maxCoeff(), 1e-15);
  const std::string path = TempPath("fk.csv");
  WriteFkCsv(path, rows);
  EXPECT_EQ(ReadFkCsv(path)[1].pose.pose_id, 6);
}

TEST(FkCsvErrors, NameLineAndField) {
  const std::string header = "pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy,qz\n";
  EXPECT_TRUE(FailsWith([] { ParseFkCsv("pose_id,X,Y,Z,theta,x,y,z,qw,qx,qy\n", "f.csv"); },
                        "f.csv", 1, "qz", "missing column"));
  EXPECT_TRUE(FailsWith([&] { ParseFkCsv(header + "1,0,0,0,0,0,0,0,0.5,0,0,0\n", "f.csv"); },
                        "f.csv", 2, "qw,qx,qy,qz", "norm 0.5"));
}

}  // namespace
}  // namespace h4
