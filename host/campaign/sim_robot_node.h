// The bus side of `h4cal sim-robot`: a SimulatedController wired to LCM. Receives
// H4_ROBOT_TARGET and answers each target on H4_TARGET_STATUS (accepted, or refused with the
// controller's reason), and at a fixed rate steps the motion on the wall clock and publishes
// H4_JOINT_STATE (noisy encoder readings, settled flag) and H4_SIM_BOARD_TRUTH (the true
// X_CT that `h4cam run --source sim` renders, also while moving).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <random>

#include <h4msgs/joint_state_t.hpp>
#include <h4msgs/robot_target_t.hpp>
#include <h4msgs/sim_board_truth_t.hpp>

#include "host/campaign/simulated_controller.h"
#include "messages/bus/lcm_bus.h"

namespace h4::host {

struct SimRobotNodeOptions {
  double rate_hz = 100.0;        ///< joint states and truths per second
  uint64_t seed = 1;             ///< encoder noise; the same seed gives the same noise draws
  double status_period_s = 5.0;  ///< one status line (spdlog info) every this many s; 0: none
};

class SimRobotNode {
 public:
  using Clock = std::chrono::steady_clock;

  /// Subscribes to H4_ROBOT_TARGET on `bus`. `bus` and `controller` must outlive the node.
  /// Throws std::invalid_argument when rate_hz is not positive and finite.
  SimRobotNode(bus::LcmBus& bus, SimulatedController& controller,
               const SimRobotNodeOptions& options = SimRobotNodeOptions{});
  SimRobotNode(const SimRobotNode&) = delete;
  SimRobotNode& operator=(const SimRobotNode&) = delete;

  /// Publishes at the rate (the first pair at once) and handles targets until `stop` is set
  /// or, when `duration` is positive, until it has elapsed. Returns when the bus keeps
  /// failing too (bus_failed() then says so; one interrupted wait is not a failure).
  void Run(const std::atomic<bool>& stop,
           std::chrono::duration<double> duration = std::chrono::duration<double>(0));
  /// Run for `duration` without a stop flag (nothing when duration <= 0).
  void RunFor(std::chrono::duration<double> duration);

  /// Steps the controller to `now` and publishes one joint state and one truth (what Run
  /// does at each tick). utime is the system clock.
  void Tick(Clock::time_point now);

  /// Builds the messages for the controller's current state (no publishing).
  h4msgs::joint_state_t MakeJointState(int64_t utime);
  h4msgs::sim_board_truth_t MakeTruth(int64_t utime) const;

  int64_t targets_received() const { return targets_received_; }
  int64_t targets_refused() const { return targets_refused_; }
  int64_t joint_states_published() const { return joint_states_published_; }
  int64_t truths_published() const { return truths_published_; }
  bool bus_failed() const { return bus_failed_; }

 private:
  void OnTarget(const h4msgs::robot_target_t& target);
  void AdvanceTo(Clock::time_point now);
  void LogStatus() const;

  bus::LcmBus& bus_;
  SimulatedController& controller_;
  SimRobotNodeOptions options_;
  std::mt19937_64 rng_;
  std::optional<Clock::time_point> last_step_;
  int64_t targets_received_ = 0;
  int64_t targets_refused_ = 0;
  int64_t joint_states_published_ = 0;
  int64_t truths_published_ = 0;
  bool bus_failed_ = false;
};

}  // namespace h4::host
