// The simulated controller on LCM; see sim_robot_node.h.
#include "host/campaign/sim_robot_node.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "common/timing/clock.h"
#include "common/timing/periodic_schedule.h"
#include "host/campaign/target_status.h"
#include "messages/channels.h"

namespace h4::host {
namespace {

constexpr int kMaxConsecutiveBusFailures = 10;

// The controller's verdicts are sent as they are: the same order as the wire's codes.
static_assert(static_cast<int8_t>(TargetStatus::kAccepted) ==
              h4msgs::target_status_t::STATUS_ACCEPTED);
static_assert(static_cast<int8_t>(TargetStatus::kUnreachable) ==
              h4msgs::target_status_t::STATUS_UNREACHABLE);
static_assert(static_cast<int8_t>(TargetStatus::kOutsideLimits) ==
              h4msgs::target_status_t::STATUS_OUTSIDE_LIMITS);
static_assert(static_cast<int8_t>(TargetStatus::kInvalid) ==
              h4msgs::target_status_t::STATUS_INVALID);

}  // namespace

SimRobotNode::SimRobotNode(bus::LcmBus& bus, SimulatedController& controller,
                           const SimRobotNodeOptions& options)
    : bus_(bus), controller_(controller), options_(options), rng_(options.seed) {
  if (!(std::isfinite(options_.rate_hz) && options_.rate_hz > 0.0)) {
    throw std::invalid_argument(
        fmt::format("sim-robot: rate must be positive, got {:f} Hz", options_.rate_hz));
  }
  bus_.Subscribe<h4msgs::robot_target_t>(
      channels::kRobotTarget, [this](const h4msgs::robot_target_t& target) { OnTarget(target); });
}

void SimRobotNode::OnTarget(const h4msgs::robot_target_t& target) {
  // Finish the motion up to now toward the old target before switching.
  AdvanceTo(Clock::now());
  ++targets_received_;
  TargetResult result;
  if (target.target_type == h4msgs::robot_target_t::TARGET_POSE) {
    result = controller_.SetPoseTarget(
        target.pose_id, EePose(target.pose[0], target.pose[1], target.pose[2], target.pose[3]));
  } else if (target.target_type == h4msgs::robot_target_t::TARGET_JOINTS) {
    result = controller_.SetJointTarget(
        target.pose_id,
        JointVector(target.joints[0], target.joints[1], target.joints[2], target.joints[3]));
  } else {
    // Not a target the controller understands: refused like any other (hold, never settle
    // for this id), and the campaign skips it with this reason.
    result = controller_.RejectTarget(
        target.pose_id,
        fmt::format("unknown target_type {} (expected TARGET_POSE 0 or TARGET_JOINTS 1)",
                    target.target_type));
  }
  // Every target is answered, a resent one too: a lost refusal costs the campaign one
  // settle timeout at most, until it sends the target again.
  bus_.Publish(channels::kTargetStatus,
               MakeTargetStatus(NowUtime(), target.pose_id, static_cast<int8_t>(result.status),
                                result.reason));
  if (!result.ok()) {
    ++targets_refused_;
    spdlog::warn("sim-robot: target for pose {} refused ({}): {}; holding, not settled",
                 target.pose_id, ToString(result.status), result.reason);
    return;
  }
  const JointVector& q = result.q_target;
  spdlog::debug("sim-robot: pose {}: moving to joints ({:.4f}, {:.4f}, {:.4f}, {:.4f}) rad",
                target.pose_id, q[0], q[1], q[2], q[3]);
}

void SimRobotNode::AdvanceTo(Clock::time_point now) {
  if (last_step_ && now > *last_step_) {
    controller_.Step(std::chrono::duration<double>(now - *last_step_).count());
  }
  if (!last_step_ || now > *last_step_) last_step_ = now;
}

h4msgs::joint_state_t SimRobotNode::MakeJointState(int64_t utime) {
  h4msgs::joint_state_t state{};
  state.utime = utime;
  state.pose_id = controller_.pose_id();
  const JointVector reading = controller_.EncoderReading(rng_);
  state.joint_count = 4;
  state.position.assign(reading.data(), reading.data() + 4);
  state.settled = controller_.settled() ? 1 : 0;
  return state;
}

h4msgs::sim_board_truth_t SimRobotNode::MakeTruth(int64_t utime) const {
  h4msgs::sim_board_truth_t truth{};
  truth.utime = utime;
  truth.pose_id = controller_.pose_id();
  const RigidTransform X_CT = controller_.true_X_CT();
  const Eigen::Vector4d q_CT = X_CT.quaternion_wxyz().normalized();
  for (int k = 0; k < 3; ++k) truth.translation[k] = X_CT.translation()[k];
  for (int k = 0; k < 4; ++k) truth.quaternion[k] = q_CT[k];
  truth.settled = controller_.settled() ? 1 : 0;
  return truth;
}

void SimRobotNode::Tick(Clock::time_point now) {
  AdvanceTo(now);
  const int64_t utime = NowUtime();
  // The truth first: a camera that renders it is then never behind the joint state that
  // announces the same settled pose.
  if (bus_.Publish(channels::kSimBoardTruth, MakeTruth(utime))) ++truths_published_;
  if (bus_.Publish(channels::kJointState, MakeJointState(utime))) ++joint_states_published_;
}

void SimRobotNode::LogStatus() const {
  const char* state = controller_.settled()   ? "settled"
                      : controller_.refused() ? "holding (target refused)"
                      : controller_.moving()  ? "moving"
                                              : "settling";
  spdlog::info(
      "sim-robot: pose {} {}; {} target(s) received, {} refused; {} joint states published",
      controller_.pose_id(), state, targets_received_, targets_refused_, joint_states_published_);
}

void SimRobotNode::Run(const std::atomic<bool>& stop, std::chrono::duration<double> duration) {
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.rate_hz));
  const Clock::time_point start = Clock::now();
  const std::optional<Clock::time_point> end =
      duration.count() > 0.0 ? std::optional<Clock::time_point>(
                                   start + std::chrono::duration_cast<Clock::duration>(duration))
                             : std::nullopt;
  PeriodicSchedule ticks(period);
  // The status line every status_period_s (none when 0), the first one period after start.
  std::optional<PeriodicSchedule> status_lines;
  if (options_.status_period_s > 0.0) {
    status_lines.emplace(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.status_period_s)));
    status_lines->Due(start);
  }
  int consecutive_failures = 0;
  while (!stop.load()) {
    Clock::time_point now = Clock::now();
    if (end && now >= *end) break;
    // After a stall the rate resumes on its grid rather than with a burst of late states.
    if (ticks.Due(now)) Tick(now);
    if (status_lines && status_lines->Due(now)) LogStatus();
    // Wait on the bus until the next tick (rounded up to whole ms, LCM's resolution), and
    // at most 100 ms so that the stop flag is seen promptly.
    Clock::time_point wake = *ticks.next();
    if (end) wake = std::min(wake, *end);
    now = Clock::now();
    const auto wait = std::clamp(std::chrono::ceil<std::chrono::milliseconds>(wake - now),
                                 std::chrono::milliseconds(0), std::chrono::milliseconds(100));
    if (bus_.Handle(wait) >= 0) {
      consecutive_failures = 0;
      continue;
    }
    // A signal interrupts LCM's wait, which then reports an error: a stop request, or (for
    // another signal) a one-off. Only an error that persists is a failed bus.
    if (stop.load()) break;
    if (++consecutive_failures >= kMaxConsecutiveBusFailures) {
      bus_failed_ = true;
      spdlog::error("sim-robot: LCM failed on {} ({} times in a row); stopping", bus_.url(),
                    consecutive_failures);
      break;
    }
  }
  if (options_.status_period_s > 0.0) LogStatus();
}

void SimRobotNode::RunFor(std::chrono::duration<double> duration) {
  if (duration.count() <= 0.0) return;  // Run would read 0 as "until stopped"
  const std::atomic<bool> never{false};
  Run(never, duration);
}

}  // namespace h4::host
