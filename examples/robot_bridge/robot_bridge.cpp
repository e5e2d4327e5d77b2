// The robot bridge; see robot_bridge.h.
#include "examples/robot_bridge/robot_bridge.h"

#include <cstdio>

#include <fmt/core.h>
#include <h4msgs/target_status_t.hpp>

#include "common/timing/clock.h"
#include "messages/channels.h"

namespace h4::example {
RobotBridge::RobotBridge(lcm::LCM& lcm, Controller& controller, RobotBridgeOptions options)
    : lcm_(lcm), controller_(controller), options_(options) {
  // A plain function and a context pointer, not subscribe(channel, &RobotBridge::OnTarget,
  // this): GCC 12 under -fsanitize=vptr miscompiles LCM's pointer-to-member dispatch
  // (cmake/H4Sanitizers.cmake).
  lcm_.subscribeFunction(channels::kRobotTarget, &RobotBridge::OnTargetMessage, this);
}

void RobotBridge::OnTargetMessage(const lcm::ReceiveBuffer*, const std::string&,
                                  const h4msgs::robot_target_t* target, RobotBridge* bridge) {
  bridge->OnTarget(target);
}

void RobotBridge::OnTarget(const h4msgs::robot_target_t* target) {
  ++targets_received_;
  // collect repeats a target until the joint states carry its id: the same target again
  // changes nothing (the robot keeps moving, or stays settled).
  if (target->pose_id == pose_id_ && !refused_) {
    Answer(pose_id_, h4msgs::target_status_t::STATUS_ACCEPTED, "");
    return;
  }
  std::string why;
  bool accepted = false;
  int8_t status = h4msgs::target_status_t::STATUS_REFUSED;  // the controller's reason says why
  if (target->target_type == h4msgs::robot_target_t::TARGET_POSE) {
    accepted = controller_.MoveToPose(
        {target->pose[0], target->pose[1], target->pose[2], target->pose[3]}, &why);
  } else if (target->target_type == h4msgs::robot_target_t::TARGET_JOINTS) {
    accepted = controller_.MoveToJoints(
        {target->joints[0], target->joints[1], target->joints[2], target->joints[3]}, &why);
  } else {
    why = fmt::format("unknown target_type {}", target->target_type);
    status = h4msgs::target_status_t::STATUS_INVALID;
  }
  // The id is taken either way: a refused pose is reported (not settled) under its own id,
  // so that the campaign never waits for an old pose (one that does not read the answer
  // below retries, then skips it).
  pose_id_ = target->pose_id;
  refused_ = !accepted;
  if (refused_) {
    ++targets_refused_;
    fmt::print(stderr, "robot_bridge: pose {} refused: {}\n", static_cast<long long>(pose_id_),
               why);
  }
  // The campaign then skips a refused pose at once, showing `why`, instead of waiting for
  // it to settle (docs/robot-bridge.md).
  if (accepted) status = h4msgs::target_status_t::STATUS_ACCEPTED;
  Answer(pose_id_, status, accepted ? "" : why);
}

void RobotBridge::Answer(int64_t pose_id, int8_t status, const std::string& why) {
  h4msgs::target_status_t answer{};
  answer.utime = NowUtime();
  answer.pose_id = pose_id;
  answer.status = status;
  answer.reason = why.substr(0, 1000);  // all the campaign shows
  lcm_.publish(channels::kTargetStatus, &answer);
}

h4msgs::joint_state_t RobotBridge::MakeJointState(int64_t utime) {
  const JointReading reading = controller_.Read();
  h4msgs::joint_state_t state{};
  state.utime = utime;
  state.pose_id = pose_id_;
  state.joint_count = 4;
  state.position.assign(reading.q.begin(), reading.q.end());
  state.settled = reading.at_rest && !refused_;
  return state;
}

void RobotBridge::PublishJointState() {
  const h4msgs::joint_state_t state = MakeJointState(NowUtime());
  lcm_.publish(channels::kJointState, &state);
}

}  // namespace h4::example
