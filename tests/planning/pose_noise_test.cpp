// Tests of each planned pose's camera noise from its corners (pose_noise.h): it scales with
// the corner noise, grows with the board's distance, and falls back where the board is not
// in the image.
#include "host/planning/pose_noise.h"

#include <gtest/gtest.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

struct CornerNoiseScene {
  RobotDescription robot = PaperAprioriRobot();
  CameraModel camera{ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")};
  BoardModel board{ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")};
};

TEST(PoseNoise, ScalesWithTheCornerNoiseAndGrowsWithDistance) {
  const CornerNoiseScene scene;
  // The camera looks up at the board from 1.05 m below B: z = -0.4 is farther than -0.5.
  const std::vector<EePose> poses = {EePose(0.0, 0.0, -0.5, 0.0), EePose(0.0, 0.0, -0.4, 0.0)};
  const PoseSigma fallback{1.0, 1.0};
  const std::vector<PoseSigma> at_01 =
      PoseSigmasFromCorners(scene.robot, scene.camera, scene.board, poses, 0.1, fallback);
  const std::vector<PoseSigma> at_02 =
      PoseSigmasFromCorners(scene.robot, scene.camera, scene.board, poses, 0.2, fallback);
  ASSERT_EQ(at_01.size(), 2u);
  EXPECT_LT(at_01[0].t, 1e-3);  // a fitted pose, not the fallback
  EXPECT_NEAR(at_02[0].t / at_01[0].t, 2.0, 1e-6);
  EXPECT_NEAR(at_02[0].r / at_01[0].r, 2.0, 1e-6);
  EXPECT_GT(at_01[1].t, at_01[0].t);
}

TEST(PoseNoise, ABoardOutOfTheImageFallsBack) {
  const CornerNoiseScene scene;
  const PoseSigma fallback{0.5, 0.25};
  const std::vector<PoseSigma> sigmas = PoseSigmasFromCorners(
      scene.robot, scene.camera, scene.board, {EePose(2.0, 0.0, -0.5, 0.0)}, 0.1, fallback);
  ASSERT_EQ(sigmas.size(), 1u);
  EXPECT_EQ(sigmas[0].t, 0.5);
  EXPECT_EQ(sigmas[0].r, 0.25);
}

}  // namespace
}  // namespace h4::host
