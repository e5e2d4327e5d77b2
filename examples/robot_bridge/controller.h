// What the robot bridge needs from a robot controller, and all it needs: the one interface
// an integrator implements for their controller (docs/robot-bridge.md). The bridge
// (robot_bridge.h) turns H4_ROBOT_TARGET messages into these calls and these readings into
// H4_JOINT_STATE messages; simulated_controller.h is the implementation the tests run.
#pragma once

#include <array>
#include <string>

namespace h4::example {

/// X, Y, Z (m) and theta (rad) of the end-effector E in the base frame B.
using EePoseTarget = std::array<double, 4>;
/// q1..q4, rad, as the encoders count them.
using JointPositions = std::array<double, 4>;

struct JointReading {
  JointPositions q{};    ///< measured encoder values, rad (not the commanded ones)
  bool at_rest = false;  ///< at the last accepted target, and still for the dwell time
};

class Controller {
 public:
  virtual ~Controller() = default;

  /// Starts moving to an end-effector pose through the controller's own inverse
  /// kinematics. False, with `why`, when the controller refuses it (out of reach, beyond
  /// its limits): the robot then holds still.
  virtual bool MoveToPose(const EePoseTarget& x_B, std::string* why) = 0;
  /// Starts moving to joint positions (the paper's control law sends these).
  virtual bool MoveToJoints(const JointPositions& q, std::string* why) = 0;
  /// The encoders now. Called at the bridge's publishing rate (100 Hz by default).
  virtual JointReading Read() = 0;
};

}  // namespace h4::example
