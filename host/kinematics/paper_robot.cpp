// The paper's robot; see paper_robot.h.
#include "host/kinematics/paper_robot.h"

namespace h4::host {

RobotDescription PaperAprioriRobot() {
  RobotDescription robot;
  robot.model12 = kPaperAprioriModel12;
  robot.X_BC = PaperX_BC();
  robot.X_TE = PaperX_TE();
  return robot;
}

}  // namespace h4::host
