// Offline board poses CSV (h4cam measure --out): rows with and without a board, exact
// round trip, malformed rows with their line and field.
#include "common/formats/board_poses_csv.h"

#include <numbers>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

const std::string kPosesHeader = "image,x,y,z,qw,qx,qy,qz,corners,rms_px,sigma_t,sigma_r\n";

TEST(BoardPosesCsv, ReadsAPoseRowAndAnEmptyRow) {
  const std::vector<BoardPoseRow> rows =
      ParseBoardPosesCsv(kPosesHeader +
                             "img_000.png,0.01,-0.02,0.8,0,0,0,1,144,0.21,0.00005,0.0004\n"
                             "img_001.png,,,,,,,,0,,,\n",
                         "b.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].image, "img_000.png");
  ASSERT_TRUE(rows[0].X_CT.has_value());
  EXPECT_EQ(rows[0].X_CT->translation(), Eigen::Vector3d(0.01, -0.02, 0.8));
  EXPECT_TRUE(rows[0].X_CT->rotation().isApprox(RotZ(std::numbers::pi), 1e-15));
  EXPECT_EQ(rows[0].corners, 144);
  EXPECT_EQ(rows[0].rms_px, 0.21);
  EXPECT_EQ(rows[0].sigma_t, 0.00005);
  EXPECT_EQ(rows[0].sigma_r, 0.0004);
  EXPECT_EQ(rows[1].image, "img_001.png");
  EXPECT_FALSE(rows[1].X_CT.has_value());
  EXPECT_EQ(rows[1].corners, 0);
  EXPECT_FALSE(rows[1].rms_px.has_value());
}

TEST(BoardPosesCsv, RoundTripIsExact) {
  std::vector<BoardPoseRow> rows(3);
  rows[0].image = "dir, with comma/a.png";
  rows[0].X_CT = RigidTransform(RotationFromRpy({0.1, -0.2, 2.9}), {1.0 / 3, -0.1, 0.75});
  rows[0].corners = 100;
  rows[0].rms_px = 0.123456789;
  rows[0].sigma_t = 1.0 / 7 * 1e-4;
  rows[0].sigma_r = 2e-4;
  rows[1].image = "b.png";
  rows[2].image = "c.png";
  rows[2].X_CT = RigidTransform();
  rows[2].corners = 4;
  rows[2].rms_px = 0.0;
  const std::string path = TempPath("board_poses.csv");
  WriteBoardPosesCsv(path, rows);
  const std::vector<BoardPoseRow> back = ReadBoardPosesCsv(path);
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back[i].image, rows[i].image);
    EXPECT_EQ(back[i].X_CT.has_value(), rows[i].X_CT.has_value());
    if (rows[i].X_CT) {
      EXPECT_EQ(back[i].X_CT->translation(), rows[i].X_CT->translation());
      EXPECT_LT((back[i].X_CT->rotation() - rows[i].X_CT->rotation()).cwiseAbs().maxCoeff(), 1e-15);
    }
    EXPECT_EQ(back[i].corners, rows[i].corners);
    EXPECT_EQ(back[i].rms_px, rows[i].rms_px);
    EXPECT_EQ(back[i].sigma_t, rows[i].sigma_t);
    EXPECT_EQ(back[i].sigma_r, rows[i].sigma_r);
  }
  EXPECT_EQ(FormatBoardPosesCsv({rows[1]}), kPosesHeader + "b.png,,,,,,,,0,,,\n");
}

TEST(BoardPosesCsvErrors, NameLineAndField) {
  ExpectEachFailsWith(
      ParseBoardPosesCsv, "b.csv",
      {{"image,x,y,z,qw,qx,qy,qz,corners,rms_px,sigma_t\n", 1, "sigma_r", "missing column"},
       // A pose with one field left empty is neither a pose nor "no board".
       {kPosesHeader + "a.png,0,0,1,1,0,,0,4,0.1,,\n", 2, "qy", "all empty"},
       {kPosesHeader + ",0,0,1,1,0,0,0,4,0.1,,\n", 2, "image", "expected a value"},
       {kPosesHeader + "a.png,0,0,1,2,0,0,0,4,0.1,,\n", 2, "qw,qx,qy,qz", "unit quaternion"},
       {kPosesHeader + "a.png,0,0,1,1,0,0,0,-4,0.1,,\n", 2, "corners", "non-negative"},
       {kPosesHeader + "a.png,0,0,1,1,0,0,0,4.5,0.1,,\n", 2, "corners", "expected an integer"},
       {kPosesHeader + "a.png,0,0,1,1,0,0,0,4,,,\n", 2, "rms_px", "reprojection RMS"},
       {kPosesHeader + "a.png,0,0,1,1,0,0,0,4,-0.1,,\n", 2, "rms_px", "non-negative"},
       {kPosesHeader + "a.png,0,0,1,1,0,0,0,4,0.1,0,0.1\n", 2, "sigma_t", "positive"}});
}

}  // namespace
}  // namespace h4
