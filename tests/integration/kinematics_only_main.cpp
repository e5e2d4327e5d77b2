// A program that uses only the kinematics and the robot file's reader (h4::kinematics,
// h4::host_formats), as a user embedding h4cal's models in a controller would: robot.yaml in, the
// joints at the workspace centre and the forward kinematics back. kinematics_only_test.sh checks it
// runs and that its link brought no LCM, NLopt, OpenCV or camera library (cmake/H4Libraries.cmake).
#include <cstdio>
#include <exception>

#include "host/formats/robot_yaml.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model12.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s ROBOT.yaml\n", argv[0]);
    return 2;
  }
  try {
    const h4::RobotDescription robot = h4::ReadRobotYaml(argv[1]);
    const h4::host::Model12 model(robot.model12, robot.assembly);
    const h4::host::EePose x = model.WorkspaceCentre();
    const h4::host::IkResult ik = model.InverseKinematics(x);
    const h4::host::FkResult fk = h4::host::ForwardKinematics(model, ik.q);
    if (!fk.ok()) {
      std::fprintf(stderr, "forward kinematics failed: %s\n", fk.message.c_str());
      return 1;
    }
    std::printf("workspace centre %.6f %.6f %.6f %.6f, round trip error %.3g m\n", x[0], x[1], x[2],
                x[3], (fk.x - x).head<3>().norm());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
