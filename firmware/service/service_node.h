// The camera service on the bus: wires a CameraService to a bus::LcmBus. Subscribes to
// H4_CAPTURE_REQUEST (and H4_SIM_BOARD_TRUTH for the synthetic camera), publishes
// H4_BOARD_POSE (each OK one followed by its H4_BOARD_CORNERS) and the H4_CAMERA_STATUS heartbeat,
// and pings the systemd watchdog with each heartbeat. Poll() is one iteration of the main loop, so
// tests drive it directly.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <h4msgs/sim_board_truth_t.hpp>

#include "common/geometry/rigid_transform.h"
#include "common/timing/clock.h"  // NowUtime, for the node and its users
#include "common/timing/periodic_schedule.h"
#include "firmware/service/camera_service.h"
#include "messages/bus/lcm_bus.h"

namespace h4::cam {

class ServiceNode {
 public:
  using Clock = std::chrono::steady_clock;

  /// Where the synthetic camera's board is to be seen next (X_CT): the sim source's SetPose.
  using ShowTruth = std::function<void(const RigidTransform& X_CT)>;

  /// Subscribes on `bus`; a `show_truth` (the sim source's; empty for a real camera) is
  /// given the true poses of H4_SIM_BOARD_TRUTH.
  ServiceNode(bus::LcmBus& bus, CameraService& service, ShowTruth show_truth,
              std::chrono::duration<double> heartbeat_period);

  /// One loop iteration: dispatches the bus messages (waiting up to `timeout` when the
  /// service needs no frame), steps the service, publishes a finished board pose and,
  /// when due, the heartbeat (the first Poll() sends one at once).
  void Poll(std::chrono::milliseconds timeout);
  /// Publishes camera_status_t now (and WATCHDOG=1 under systemd).
  void PublishStatus();

  int64_t board_poses_published() const { return board_poses_published_; }
  int64_t board_corners_published() const { return board_corners_published_; }
  int64_t statuses_published() const { return statuses_published_; }
  /// Sim truths refused (not finite, not a unit quaternion).
  int64_t invalid_truths() const { return invalid_truths_; }

 private:
  void OnTruth(const h4msgs::sim_board_truth_t& truth);

  bus::LcmBus& bus_;
  CameraService& service_;
  ShowTruth show_truth_;
  PeriodicSchedule heartbeats_;
  int64_t board_poses_published_ = 0;
  int64_t board_corners_published_ = 0;
  int64_t statuses_published_ = 0;
  int64_t invalid_truths_ = 0;
  /// The newest valid truth not yet rendered: truths arrive at the robot's 100 Hz, faster
  /// than a frame renders, so the handler only stores them and Poll() renders the newest.
  std::optional<RigidTransform> pending_truth_;
};

/// X_CT of a truth message; nullopt when a value is not finite or the quaternion is not
/// unit within 1e-6 (then `why` says which).
std::optional<RigidTransform> TruthPose(const h4msgs::sim_board_truth_t& truth, std::string* why);

}  // namespace h4::cam
