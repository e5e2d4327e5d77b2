// Tests of the candidate set of pose planning: every candidate is reachable by the a priori
// robot and shows the whole board in the simulated camera (its outer corners projected
// here independently, through X_CT = inv(X_BC) X_BE inv(X_TE)), and the filter rejects
// poses that break each rule.
#include "host/planning/candidate_poses.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/number_text.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "tests/support/options_check.h"

namespace h4::host {
namespace {

BoardModel DemoBoard() {
  return BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml"));
}
CameraModel DemoCamera() {
  return CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml"));
}

// True when every corner of the board (not only the outer ones) projects inside the image
// with `margin_px`.
bool WholeBoardInImage(const RobotDescription& robot, const CameraModel& camera,
                       const BoardModel& board, const EePose& x_B, double margin_px) {
  const RigidTransform X_BE(Eigen::AngleAxisd(x_B[3], Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                            x_B.head<3>());
  const RigidTransform X_CT = robot.X_BC.inverse() * X_BE * robot.X_TE.inverse();
  for (const Eigen::Vector3d& p_TQ : board.corners()) {
    Eigen::Vector2d uv;
    if (!camera.Project(X_CT * p_TQ, &uv)) return false;
    if (uv.x() < margin_px || uv.y() < margin_px || uv.x() > camera.width() - 1 - margin_px ||
        uv.y() > camera.height() - 1 - margin_px) {
      return false;
    }
  }
  return true;
}

TEST(CandidatePoses, EveryCandidateIsReachableAndShowsTheWholeBoard) {
  const RobotDescription robot = PaperAprioriRobot();
  const CameraModel camera = DemoCamera();
  const BoardModel board = DemoBoard();
  const CandidateOptions options;
  const CandidateSet set = MakeCandidateSet(robot, camera, board, options);
  ASSERT_GT(set.poses.size(), 100u) << set.Summary();
  const Model12 model(robot.model12, robot.assembly);
  for (const CandidatePose& pose : set.poses) {
    const IkResult ik = model.InverseKinematics(pose.x_B);
    ASSERT_TRUE(ik.ok()) << pose.x_B.transpose();
    EXPECT_LT((ik.q - pose.q).norm(), 1e-12);
    EXPECT_TRUE(WholeBoardInImage(robot, camera, board, pose.x_B, options.image_margin_px))
        << pose.x_B.transpose();
  }
}

// plan.csv holds the designed grid values: -0.15, not -0.15000000000000002 (issue 26).
TEST(CandidatePoses, PositionsAreTheDesignedGridValuesWrittenShort) {
  const CandidateSet set =
      MakeCandidateSet(PaperAprioriRobot(), DemoCamera(), DemoBoard(), CandidateOptions{});
  ASSERT_FALSE(set.poses.empty());
  for (const CandidatePose& pose : set.poses) {
    for (int i = 0; i < 3; ++i) {
      const std::string text = FormatDouble(pose.x_B[i], "x");
      EXPECT_LE(text.size(), 6u) << text;
    }
  }
}

TEST(CandidatePoses, SomeGridPosesAreRejectedForTheImageAndTheRestKept) {
  // A wide grid must lose poses to the image border, else the filter is not filtering.
  const RobotDescription robot = PaperAprioriRobot();
  CandidateOptions options;
  options.half_extent = Eigen::Vector3d(0.3, 0.3, 0.1);
  options.position_step = 0.05;
  const CandidateSet set = MakeCandidateSet(robot, DemoCamera(), DemoBoard(), options);
  EXPECT_GT(set.rejected[static_cast<size_t>(CandidateVerdict::kOutOfImage)], 0) << set.Summary();
  EXPECT_GT(set.poses.size(), 0u) << set.Summary();
  int rejected = 0;
  for (int count : set.rejected) rejected += count;
  EXPECT_EQ(rejected + static_cast<int>(set.poses.size()), set.examined);
}

// Every corner of the board at pose x_B lies in the field the camera model images one to one.
bool WholeBoardInValidField(const RobotDescription& robot, const CameraModel& camera,
                            const BoardModel& board, const EePose& x_B) {
  const RigidTransform X_BE(Eigen::AngleAxisd(x_B[3], Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                            x_B.head<3>());
  const RigidTransform X_CT = robot.X_BC.inverse() * X_BE * robot.X_TE.inverse();
  for (const Eigen::Vector3d& p_TQ : board.corners()) {
    if (!camera.InValidField(X_CT * p_TQ)) return false;
  }
  return true;
}

// Issue 27 point 3: with radtan k1 = -5 (the image folds at 14.5 deg) plan kept more
// candidates than with the nominal camera (4722 against 3661), and an equidistant k1 = -30
// (folding at 6 deg) kept 765: corners past the fold project back inside the image.
TEST(CandidatePoses, CornersPastTheLensFoldAreOutOfTheImage) {
  const RobotDescription robot = PaperAprioriRobot();
  const BoardModel board = DemoBoard();
  const CameraModel nominal = DemoCamera();
  const CandidateSet nominal_set = MakeCandidateSet(robot, nominal, board, CandidateOptions{});
  CameraIntrinsics radtan = nominal.intrinsics();
  radtan.distortion_model = DistortionModel::kRadTan;
  radtan.distortion = Eigen::VectorXd::Zero(5);
  radtan.distortion[0] = -5.0;
  CameraIntrinsics fisheye = nominal.intrinsics();
  fisheye.distortion_model = DistortionModel::kEquidistant;
  fisheye.distortion = Eigen::Vector4d(-30.0, 0.0, 0.0, 0.0);
  for (const CameraIntrinsics& intrinsics : {radtan, fisheye}) {
    const CameraModel folding(intrinsics);
    ASSERT_LT(folding.max_field_angle(), 0.3);
    const CandidateSet set = MakeCandidateSet(robot, folding, board, CandidateOptions{});
    EXPECT_LE(set.poses.size(), nominal_set.poses.size()) << set.Summary();
    for (const CandidatePose& pose : set.poses) {
      EXPECT_TRUE(WholeBoardInValidField(robot, folding, board, pose.x_B))
          << ToString(intrinsics.distortion_model) << ": " << pose.x_B.transpose();
    }
  }
}

TEST(CandidatePoses, JointRangeDepthAndTiltRulesReject) {
  const RobotDescription robot = PaperAprioriRobot();
  const CameraModel camera = DemoCamera();
  const BoardModel board = DemoBoard();
  const EePose centre(0.0, 0.0, -0.45, 0.0);

  CandidateOptions options;
  EXPECT_EQ(CandidateFilter(robot, camera, board, options).Check(centre, nullptr),
            CandidateVerdict::kOk);
  EXPECT_EQ(
      CandidateFilter(robot, camera, board, options).Check(EePose(0.0, 0.0, -3.0, 0.0), nullptr),
      CandidateVerdict::kUnreachable);

  CandidateOptions narrow_joints = options;
  narrow_joints.joint_range = Eigen::Vector2d(-1e-3, 1e-3);
  EXPECT_EQ(CandidateFilter(robot, camera, board, narrow_joints).Check(centre, nullptr),
            CandidateVerdict::kJointRange);

  CandidateOptions near_focus = options;
  near_focus.max_depth = near_focus.min_depth + 1e-3;
  EXPECT_EQ(CandidateFilter(robot, camera, board, near_focus).Check(centre, nullptr),
            CandidateVerdict::kDepth);

  CandidateOptions strict_tilt = options;
  strict_tilt.max_tilt = 1e-6;
  EXPECT_EQ(CandidateFilter(robot, camera, board, strict_tilt).Check(centre, nullptr),
            CandidateVerdict::kTilt);
}

// Nacelle angles to +-60 deg reach the singularity where theta stops being held by the
// joints (the gain |d theta / dq| grows without bound); the filter keeps only poses whose
// a priori gain is within the limit, and rejects a pose next to the singularity.
TEST(CandidatePoses, PosesNearTheThetaSingularityAreRejected) {
  const RobotDescription robot = PaperAprioriRobot();
  const CameraModel camera = DemoCamera();
  const BoardModel board = DemoBoard();
  CandidateOptions options;
  options.position_step = 0.05;
  options.theta.clear();
  for (double deg = -60.0; deg <= 60.0; deg += 10.0) {
    options.theta.push_back(RadiansFromDegrees(deg));
  }
  const CandidateSet set = MakeCandidateSet(robot, camera, board, options);
  EXPECT_GT(set.rejected[static_cast<size_t>(CandidateVerdict::kNearSingular)], 0) << set.Summary();
  const Model12 model(robot.model12, robot.assembly);
  for (const CandidatePose& pose : set.poses) {
    EXPECT_LE(ThetaJointGain(model, pose.q, pose.x_B), options.max_theta_gain)
        << pose.x_B.transpose();
  }
  // A planned pose of the wide set at which forward kinematics of a simulated true robot
  // had no solution at its noisy joints.
  const EePose near_singular(-0.1, 0.075, -0.475, RadiansFromDegrees(60.0));
  EXPECT_EQ(CandidateFilter(robot, camera, board, options).Check(near_singular, nullptr),
            CandidateVerdict::kNearSingular);
  CandidateOptions no_limit = options;
  no_limit.max_theta_gain = INFINITY;
  EXPECT_EQ(CandidateFilter(robot, camera, board, no_limit).Check(near_singular, nullptr),
            CandidateVerdict::kOk);
}

TEST(CandidatePoses, InvalidOptionsAreRefusedWithTheField) {
  CandidateOptions options;
  options.position_step = 0.0;
  EXPECT_TRUE(RefusedNaming(options, "position_step"));
  EXPECT_THROW(MakeCandidateSet(PaperAprioriRobot(), DemoCamera(), DemoBoard(), options),
               std::invalid_argument);
  CandidateOptions no_gain;
  no_gain.max_theta_gain = 0.0;
  EXPECT_TRUE(RefusedNaming(no_gain, "max_theta_gain"));
}

}  // namespace
}  // namespace h4::host
