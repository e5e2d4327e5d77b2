// The simulated controller of the robot bridge example; see simulated_controller.h.
#include "examples/robot_bridge/simulated_controller.h"

#include "host/formats/robot_yaml.h"
#include "host/simulation/truth_file.h"

namespace h4::example {
namespace {

/// The Controller answer to a target: accepted, or refused with the controller's reason.
bool TargetAccepted(const host::TargetResult& result, std::string* why) {
  if (!result.ok()) *why = result.reason;
  return result.ok();
}

}  // namespace

SimulatedH4Controller::SimulatedH4Controller(const std::string& truth_path,
                                             const std::string& robot_path,
                                             const host::SimulatedControllerOptions& options) {
  const host::SimulatedRobot truth = host::ReadTruthYaml(truth_path).robot;
  const RobotDescription apriori = ReadRobotYaml(robot_path);
  robot_ = std::make_unique<host::SimulatedController>(truth, apriori.model12, apriori.assembly,
                                                       options);
}

SimulatedH4Controller::~SimulatedH4Controller() = default;

bool SimulatedH4Controller::MoveToPose(const EePoseTarget& x_B, std::string* why) {
  AdvanceToNow();
  return TargetAccepted(
      robot_->SetPoseTarget(next_id_++, host::EePose(x_B[0], x_B[1], x_B[2], x_B[3])), why);
}

bool SimulatedH4Controller::MoveToJoints(const JointPositions& q, std::string* why) {
  AdvanceToNow();
  return TargetAccepted(
      robot_->SetJointTarget(next_id_++, host::JointVector(q[0], q[1], q[2], q[3])), why);
}

JointReading SimulatedH4Controller::Read() {
  AdvanceToNow();
  const host::JointVector q = robot_->EncoderReading(rng_);
  JointReading reading;
  for (int i = 0; i < 4; ++i) reading.q[static_cast<size_t>(i)] = q[i];
  reading.at_rest = robot_->settled();
  return reading;
}

RigidTransform SimulatedH4Controller::true_X_CT() const { return robot_->true_X_CT(); }

void SimulatedH4Controller::AdvanceToNow() {
  const auto now = std::chrono::steady_clock::now();
  if (last_step_) robot_->Step(std::chrono::duration<double>(now - *last_step_).count());
  last_step_ = now;
}

}  // namespace h4::example
