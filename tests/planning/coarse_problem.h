// The planning problem the planning tests share: the paper's a priori robot, the simulated
// camera and the 6x6 aprilgrid, on a coarser candidate grid than the default (5 cm steps)
// so that each test takes about a second.
#pragma once

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/pose_planner.h"

namespace h4::host {

inline const PlanningProblem& CoarseProblem() {
  static const PlanningProblem problem = [] {
    PlanningProblemOptions options;
    options.candidates.position_step = 0.05;
    return MakePlanningProblem(
        PaperAprioriRobot(),
        CameraModel(ReadCameraYaml(H4_SOURCE_DIR "/boards/sim_camera_1024x768.yaml")),
        BoardModel(ReadBoardYaml(H4_SOURCE_DIR "/boards/aprilgrid_6x6_30mm.yaml")), options);
  }();
  return problem;
}

}  // namespace h4::host
