// Tests of the check of a plan against the robot's reach (issue 26): what a controller
// refuses (the a priori Model 12 has no inverse kinematics, a joint outside its range) is
// named by pose id before the robot moves, and `plan` chooses no such pose.
#include "host/planning/reach_check.h"

#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/units.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/candidate_poses.h"

namespace h4::host {
namespace {

PosePlan PlanOf(const std::vector<EePose>& poses) {
  PosePlan plan;
  for (size_t i = 0; i < poses.size(); ++i) plan.push_back({static_cast<int64_t>(i + 1), poses[i]});
  return plan;
}

TEST(ReachCheck, NamesEachPoseOutOfReachByIdPositionAndLeg) {
  const RobotDescription robot = PaperAprioriRobot();
  const PosePlan plan = PlanOf(
      {EePose(0.0, 0.0, -0.45, 0.0), EePose(0.0, 0.0, -1.5, 0.0), EePose(0.1, 0.0, -0.5, 0.2)});
  const std::vector<UnreachablePose> out = UnreachablePoses(robot, plan, std::nullopt);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].pose_id, 2);
  EXPECT_EQ(Describe(out[0]),
            "pose 2 (X 0.0, Y 0.0, Z -1500.0 mm, theta 0.0 deg): legs 1, 2, 3, 4 out of reach "
            "(no inverse kinematics)");
  EXPECT_TRUE(UnreachablePoses(robot, GridPosePlan(), std::nullopt).empty())
      << "the paper's grid is within the paper robot's reach";
}

TEST(ReachCheck, AJointOutsideTheRangeIsNamed) {
  const RobotDescription robot = PaperAprioriRobot();
  const PosePlan plan = PlanOf({EePose(0.0, 0.0, -0.45, 0.0)});
  const Eigen::Vector2d narrow(RadiansFromDegrees(170.0), RadiansFromDegrees(175.0));
  const std::vector<UnreachablePose> out = UnreachablePoses(robot, plan, narrow);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NE(out[0].why.find("outside the joint range 170.0..175.0 deg"), std::string::npos)
      << out[0].why;
}

// `plan` and `collect --robot` decide by the same computation: no candidate of a plan is
// one that collect would refuse to send, with or without a joint range.
TEST(ReachCheck, NoCandidateOfPlanIsOutOfReach) {
  const RobotDescription robot = PaperAprioriRobot();
  const CameraModel camera(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml"));
  const BoardModel board(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml"));
  CandidateOptions options;
  options.position_step = 0.1;
  options.joint_range = Eigen::Vector2d(RadiansFromDegrees(-150.0), RadiansFromDegrees(150.0));
  const CandidateSet set = MakeCandidateSet(robot, camera, board, options);
  ASSERT_GT(set.poses.size(), 10u) << set.Summary();
  EXPECT_GT(set.rejected[static_cast<size_t>(CandidateVerdict::kJointRange)], 0) << set.Summary();
  PosePlan plan;
  for (const CandidatePose& pose : set.poses) {
    plan.push_back({static_cast<int64_t>(plan.size() + 1), pose.x_B});
  }
  EXPECT_TRUE(UnreachablePoses(robot, plan, options.joint_range).empty());
}

}  // namespace
}  // namespace h4::host
