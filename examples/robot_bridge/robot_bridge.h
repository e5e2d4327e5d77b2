// The robot side of a calibration campaign on LCM, for any controller behind the
// Controller interface (docs/robot-bridge.md): takes H4_ROBOT_TARGET, calls the controller,
// answers each target on H4_TARGET_STATUS (accepted, or refused with the controller's
// reason), and publishes H4_JOINT_STATE at a steady rate with the pose id of the last target
// and the settled flag. Uses only LCM and the generated h4msgs types, as an integrator's
// bridge would.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include <h4msgs/joint_state_t.hpp>
#include <h4msgs/robot_target_t.hpp>
#include <lcm/lcm-cpp.hpp>

#include "examples/robot_bridge/controller.h"

namespace h4::example {

struct RobotBridgeOptions {
  double rate_hz = 100.0;  ///< joint states per second (the campaign pairs within 0.2 s)
};

class RobotBridge {
 public:
  /// Subscribes to H4_ROBOT_TARGET on `lcm`. `lcm` and `controller` must outlive the bridge.
  RobotBridge(lcm::LCM& lcm, Controller& controller, RobotBridgeOptions options = {});

  /// One reading of the controller as a joint state, stamped `utime` (us since the epoch).
  h4msgs::joint_state_t MakeJointState(int64_t utime);
  /// Publishes MakeJointState(now) on H4_JOINT_STATE.
  void PublishJointState();
  /// Handles targets and publishes at the rate until `stop` is set; `each_tick` (may be
  /// empty) runs before every joint state (the simulation publishes its board truth there).
  template <class EachTick>
  void Run(const std::atomic<bool>& stop, EachTick each_tick);

  int64_t pose_id() const { return pose_id_; }
  int64_t targets_received() const { return targets_received_; }
  int64_t targets_refused() const { return targets_refused_; }

 private:
  static void OnTargetMessage(const lcm::ReceiveBuffer*, const std::string&,
                              const h4msgs::robot_target_t* target, RobotBridge* bridge);
  void OnTarget(const h4msgs::robot_target_t* target);
  /// Publishes the answer to the target of `pose_id` on H4_TARGET_STATUS.
  void Answer(int64_t pose_id, int8_t status, const std::string& why);

  lcm::LCM& lcm_;
  Controller& controller_;
  RobotBridgeOptions options_;
  int64_t pose_id_ = -1;  ///< the last target's id, accepted or not
  bool refused_ = false;  ///< the last target was refused: never settled until a new one
  int64_t targets_received_ = 0;
  int64_t targets_refused_ = 0;
};

template <class EachTick>
void RobotBridge::Run(const std::atomic<bool>& stop, EachTick each_tick) {
  using Clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.rate_hz));
  Clock::time_point next = Clock::now();
  while (!stop.load()) {
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now());
    if (wait.count() > 0) {
      lcm_.handleTimeout(static_cast<int>(wait.count()));  // a target, or the tick's time
      continue;
    }
    each_tick();
    PublishJointState();
    next += period;
    if (next < Clock::now()) next = Clock::now() + period;  // fell behind: do not burst
  }
}

}  // namespace h4::example
