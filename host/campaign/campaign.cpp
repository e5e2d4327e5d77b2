// The calibration campaign state machine; see campaign.h.
#include "host/campaign/campaign.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <h4msgs/capture_request_t.hpp>
#include <h4msgs/robot_target_t.hpp>
#include <spdlog/spdlog.h>

#include "common/formats/corners_csv.h"
#include "common/formats/format_error.h"
#include "common/text/enum_names.h"
#include "common/timing/clock.h"
#include "common/units.h"
#include "host/campaign/target_status.h"
#include "messages/channels.h"

namespace h4::host {
namespace {

constexpr EnumNames<CampaignMode, CampaignMode::kPassive> kCampaignModeNames = {"active", "manual",
                                                                                "passive"};

const char* ModeName(CampaignMode mode) { return kCampaignModeNames.NameOf(mode); }

}  // namespace

Campaign::Campaign(bus::LcmBus& bus, PosePlan plan, DatasetJournal& journal,
                   CampaignOptions options)
    : bus_(bus), plan_(std::move(plan)), journal_(journal), options_(options) {
  for (size_t i = 0; i < plan_.size(); ++i) {
    const int64_t id = plan_[i].pose_id;
    if (journal_.Contains(id)) continue;
    const auto unreachable = options_.unreachable.find(id);
    if (options_.mode == CampaignMode::kActive && unreachable != options_.unreachable.end()) {
      skipped_.push_back({id, "not sent: " + unreachable->second, true});
      continue;
    }
    pending_.push_back(i);
    history_.Track(id);
  }
  for (const DatasetRow& row : journal_.rows()) {
    if (!IsPlanned(row.pose_id)) {
      spdlog::warn("{}: pose {} is not in the pose plan (kept, not measured again)",
                   journal_.path(), row.pose_id);
    }
  }
  bus_.Subscribe<h4msgs::joint_state_t>(
      channels::kJointState, [this](const h4msgs::joint_state_t& m) { OnJointState(m); });
  bus_.Subscribe<h4msgs::target_status_t>(
      channels::kTargetStatus, [this](const h4msgs::target_status_t& m) { OnTargetStatus(m); });
  bus_.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose,
                                       [this](const h4msgs::board_pose_t& m) { OnBoardPose(m); });
  bus_.Subscribe<h4msgs::camera_status_t>(
      channels::kCameraStatus, [this](const h4msgs::camera_status_t& m) { OnCameraStatus(m); });
  spdlog::info("campaign ({} mode): {} poses planned, {} already in {}, {}{} to measure",
               ModeName(options_.mode), plan_.size(),
               plan_.size() - pending_.size() - skipped_.size(), journal_.path(),
               skipped_.empty() ? "" : fmt::format("{} out of reach (not sent), ", skipped_.size()),
               pending_.size());
}

Campaign::Campaign(bus::LcmBus& bus, PosePlan plan, DatasetJournal& journal,
                   CornersJournal& corners, CampaignOptions options)
    : Campaign(bus, std::move(plan), journal, std::move(options)) {
  corners_ = &corners;
  bus_.Subscribe<h4msgs::board_corners_t>(
      channels::kBoardCorners, [this](const h4msgs::board_corners_t& m) { OnBoardCorners(m); });
}

int Campaign::done_count() const {
  return static_cast<int>(plan_.size() - pending_.size() + next_);
}

bool Campaign::IsPlanned(int64_t pose_id) const {
  return std::any_of(plan_.begin(), plan_.end(),
                     [pose_id](const PlannedPose& p) { return p.pose_id == pose_id; });
}

void Campaign::WarnThrottled(bus::WarningThrottle& throttle, const std::string& text) {
  int64_t suppressed = 0;
  if (!throttle.Allow(bus::WarningThrottle::Clock::now(), &suppressed)) return;
  if (suppressed > 0) {
    spdlog::warn("{} ({} similar warnings not logged)", text, suppressed);
  } else {
    spdlog::warn("{}", text);
  }
}

void Campaign::OnCameraStatus(const h4msgs::camera_status_t& msg) {
  camera_heard_ = true;
  ++camera_statuses_;
  if (options_.mode != CampaignMode::kPassive) camera_clock_.Add(msg.utime, NowUtime());
}

void Campaign::OnJointState(const h4msgs::joint_state_t& msg) {
  ++counters_.joint_states;
  JointReading reading;
  std::string why;
  if (CheckJointState(msg, &reading, &why) != MessageProblem::kNone) {
    ++counters_.impossible_values;
    WarnThrottled(joint_state_warnings_, fmt::format("ignored a joint state: {} ({} so far)", why,
                                                     counters_.impossible_values));
    return;
  }
  if (options_.mode != CampaignMode::kPassive &&
      robot_staleness_.Stale(reading.utime, NowUtime())) {
    ++counters_.stale_joint_states;
    WarnThrottled(joint_state_warnings_,
                  fmt::format("ignored a joint state stamped over 2 s before the robot's latest "
                              "ones (replayed or held back; {} so far)",
                              counters_.stale_joint_states));
    return;
  }
  joints_heard_ = true;
  if (options_.mode != CampaignMode::kPassive) robot_clock_.Add(reading.utime, NowUtime());
  history_.Add(reading);
  if (finished()) return;
  if (options_.mode == CampaignMode::kActive && phase_ == Phase::kSettling && reading.settled &&
      reading.pose_id == current().pose_id) {
    settled_seen_ = true;
  }
  if (options_.mode == CampaignMode::kManual && phase_ == Phase::kSettling) {
    if (!reading.settled) moved_since_capture_ = true;
    if (reading.settled && moved_since_capture_) settled_seen_ = true;
  }
}

// Only while the robot is awaited at the current pose: a refusal of another pose id is an
// answer to an earlier target (or another campaign's), and a robot that answers nothing
// keeps today's behaviour, the settle timeout.
void Campaign::OnTargetStatus(const h4msgs::target_status_t& msg) {
  if (options_.mode != CampaignMode::kActive || finished() || phase_ != Phase::kSettling ||
      msg.pose_id != current().pose_id) {
    return;
  }
  if (std::optional<std::string> refusal = DescribeRefusal(msg)) refusal_ = std::move(refusal);
}

bool Campaign::Record(const h4msgs::board_pose_t& msg, std::optional<int64_t> joint_pose_id,
                      std::string* why) {
  const int64_t tolerance_us = static_cast<int64_t>(options_.pair_tolerance_s * 1e6);
  const std::optional<JointReading> joints =
      history_.FindSettled(joint_pose_id, msg.utime, tolerance_us);
  if (!joints) {
    ++counters_.unpaired;
    *why = fmt::format("no settled joint reading within {:.3f} s of the measurement{}",
                       options_.pair_tolerance_s, ClockSkewNote());
    return false;
  }
  try {
    journal_.Append(MakeDatasetRow(msg, *joints));
  } catch (const std::invalid_argument& e) {  // a row the dataset's reader would refuse
    ++counters_.impossible_values;
    *why = e.what();
    return false;
  }
  history_.Forget(msg.pose_id);
  PairCornersOf(msg.pose_id, msg.utime);
  return true;
}

// The corners belong to the measurement with the same pose id and utime (board_corners_t.lcm):
// those of an earlier attempt at the pose (moved, unpaired) are not this row's.
void Campaign::OnBoardCorners(const h4msgs::board_corners_t& msg) {
  ++counters_.board_corners;
  if (corners_ == nullptr || msg.pose_id < 0 || corners_->Contains(msg.pose_id)) return;
  const auto awaiting = awaiting_corners_.find(msg.pose_id);
  if (awaiting != awaiting_corners_.end() && awaiting->second == msg.utime) {
    if (AppendCorners(msg)) awaiting_corners_.erase(awaiting);
    return;
  }
  if (journal_.Contains(msg.pose_id)) {
    ++counters_.unusable_corners;
    spdlog::debug("corners of pose {}: not those of its recorded measurement", msg.pose_id);
    return;
  }
  early_corners_[msg.pose_id] = msg;
  if (early_corners_.size() > kEarlyCornersKept) {
    const auto oldest = std::min_element(
        early_corners_.begin(), early_corners_.end(),
        [](const auto& a, const auto& b) { return a.second.utime < b.second.utime; });
    early_corners_.erase(oldest);
  }
}

void Campaign::PairCornersOf(int64_t pose_id, int64_t utime) {
  if (corners_ == nullptr || corners_->Contains(pose_id)) return;
  const auto early = early_corners_.find(pose_id);
  if (early != early_corners_.end()) {
    const h4msgs::board_corners_t msg = early->second;
    early_corners_.erase(early);
    if (msg.utime == utime && AppendCorners(msg)) return;
  }
  awaiting_corners_[pose_id] = utime;
}

// Written only if the file will read back: the rows go through the CSV reader first
// (common/formats/README.md#board-corners-csv: bounds, one row per corner).
bool Campaign::AppendCorners(const h4msgs::board_corners_t& msg) {
  std::string text = CornersCsvHeader(true) + "\n";
  try {
    for (size_t i = 0; i < static_cast<size_t>(msg.corner_count); ++i) {
      const CornerObservation c{msg.pose_id, msg.tag_id[i], msg.corner[i],
                                msg.u[i],    msg.v[i],      msg.sigma_px[i]};
      text += CornersCsvLine(c, true) + "\n";
    }
    const std::vector<CornerObservation> rows = ParseCornersCsv(text, channels::kBoardCorners);
    if (rows.empty()) throw std::invalid_argument("no corners");
    corners_->Append(rows);
    return true;
  } catch (const std::invalid_argument& e) {
    ++counters_.unusable_corners;
    WarnThrottled(corners_warnings_,
                  fmt::format("ignored the corners of pose {}: {}", msg.pose_id, e.what()));
  } catch (const FormatError& e) {
    ++counters_.unusable_corners;
    WarnThrottled(corners_warnings_,
                  fmt::format("ignored the corners of pose {}: {}", msg.pose_id, e.what()));
  }
  return false;
}

std::vector<int64_t> Campaign::poses_without_corners() const {
  std::vector<int64_t> poses;
  for (const auto& [pose_id, utime] : awaiting_corners_) poses.push_back(pose_id);
  return poses;
}

void Campaign::OnBoardPose(const h4msgs::board_pose_t& msg) {
  ++counters_.board_poses;
  if (msg.pose_id < 0) return;  // free-running measurements are not campaign data
  if (journal_.Contains(msg.pose_id)) {
    ++counters_.duplicates;
    spdlog::debug("pose {}: already recorded, later measurement ignored", msg.pose_id);
    return;
  }
  const bool passive = options_.mode == CampaignMode::kPassive;
  const bool awaited =
      !finished() && phase_ == Phase::kMeasuring && msg.pose_id == current().pose_id;
  if (!(passive ? IsPlanned(msg.pose_id) : awaited)) {
    ++counters_.unexpected_pose_ids;
    WarnThrottled(
        unexpected_pose_warnings_,
        fmt::format("ignored a measurement of pose {}: {} ({} so far)", msg.pose_id,
                    IsPlanned(msg.pose_id) ? "not the pose being measured" : "not in the plan",
                    counters_.unexpected_pose_ids));
    return;
  }
  std::string why;
  if (msg.status != h4msgs::board_pose_t::STATUS_OK) {
    why = "camera reported '" + BoardPoseStatusName(msg.status) + "'";
  } else if (const MessageProblem problem = CheckBoardPose(msg, &why);
             problem != MessageProblem::kNone) {
    // No camera sends this: a foreign or corrupted message. It must not cost the awaited
    // pose an attempt, so the campaign keeps waiting for the real answer (or the timeout).
    int64_t& count = problem == MessageProblem::kNonPhysicalCovariance
                         ? counters_.nonphysical_covariances
                         : counters_.impossible_values;
    ++count;
    WarnThrottled(measurement_warnings_,
                  fmt::format("ignored a measurement: {} ({} so far)", why, count));
    return;
  } else {
    // Active mode pairs with the robot's report for this very pose id; a robot moved by hand
    // (manual) reports no campaign ids, so only time pairs.
    const std::optional<int64_t> joint_pose_id =
        options_.mode == CampaignMode::kManual ? std::nullopt : std::optional<int64_t>(msg.pose_id);
    if (Record(msg, joint_pose_id, &why)) {
      spdlog::debug("pose {} recorded", msg.pose_id);
      if (awaited) recorded_current_ = true;
      if (passive) {
        // Keep done_count() meaningful: a passive campaign advances as poses arrive.
        auto it = std::find_if(pending_.begin() + static_cast<long>(next_), pending_.end(),
                               [&](size_t i) { return plan_[i].pose_id == msg.pose_id; });
        if (it != pending_.end()) {
          std::iter_swap(pending_.begin() + static_cast<long>(next_), it);
          ++next_;
        }
      }
      return;
    }
  }
  if (passive) {
    spdlog::info("pose {}: measurement not used: {}", msg.pose_id, why);
  } else {
    failed_attempt_ = why;
  }
}

bool Campaign::PublishTarget(const PlannedPose& pose, Clock::time_point now) {
  h4msgs::robot_target_t target{};
  target.utime = NowUtime();
  target.pose_id = pose.pose_id;
  for (int i = 0; i < 4; ++i) target.pose[i] = pose.x[i];
  target.target_type = h4msgs::robot_target_t::TARGET_POSE;
  if (options_.control_law) {
    std::string why;
    const std::optional<JointVector> q = options_.control_law(pose.x, &why);
    if (!q) {
      spdlog::warn("pose {}: skipped: the control law cannot reach it: {}", pose.pose_id, why);
      skipped_.push_back({pose.pose_id, "control law: " + why});
      NextPose();
      return false;
    }
    target.target_type = h4msgs::robot_target_t::TARGET_JOINTS;
    for (int i = 0; i < 4; ++i) target.joints[i] = (*q)[i];
  }
  bus_.Publish(channels::kRobotTarget, target);
  target_sent_ = now;
  return true;
}

void Campaign::NextPose() {
  ++next_;
  phase_ = Phase::kSendTarget;
  attempt_ = 0;
  settled_seen_ = false;
  moved_since_capture_ = false;
  failed_attempt_.reset();
  refusal_.reset();
  recorded_current_ = false;
}

void Campaign::Retry(Phase phase, const std::string& why, Clock::time_point now) {
  const PlannedPose& pose = current();
  if (attempt_ >= options_.retries) {
    spdlog::warn("pose {}: skipped after {} attempts: {}", pose.pose_id, attempt_ + 1, why);
    skipped_.push_back({pose.pose_id, why});
    NextPose();
    return;
  }
  ++attempt_;
  ++counters_.retries;
  spdlog::warn("pose {}: {}; retrying ({}/{})", pose.pose_id, why, attempt_, options_.retries);
  phase_ = phase;
  phase_start_ = now;
  failed_attempt_.reset();
}

void Campaign::RetryUnsettled(Clock::time_point now) {
  const int64_t pose_id = current().pose_id;
  const size_t skipped_before = skipped_.size();
  const std::string hint =
      joints_heard_ ? "" : " (no joint state heard at all: is the robot controller running?)";
  Retry(options_.mode == CampaignMode::kActive ? Phase::kSendTarget : Phase::kSettling,
        fmt::format("robot not settled after {:.1f} s{}", options_.settle_timeout_s, hint), now);
  if (skipped_.size() == skipped_before) return;  // retrying, not skipped
  unsettled_in_a_row_.push_back(pose_id);
  const int limit = options_.max_unsettled_in_a_row;
  if (options_.mode != CampaignMode::kActive || limit <= 0 ||
      static_cast<int>(unsettled_in_a_row_.size()) < limit || finished()) {
    return;
  }
  throw std::runtime_error(fmt::format(
      "the robot never settled at {} poses in a row ({}; {} attempt(s) of {:.1f} s each): is "
      "it stuck, or does its controller never report joint_state_t.settled? Stopped; the "
      "dataset {} keeps its {} row(s): run the same command again to resume",
      unsettled_in_a_row_.size(), fmt::join(unsettled_in_a_row_, ", "), options_.retries + 1,
      options_.settle_timeout_s, journal_.path(), journal_.rows().size()));
}

void Campaign::SkipRefused() {
  const int64_t pose_id = current().pose_id;
  spdlog::warn("pose {} refused by the robot: {}; skipped", pose_id, *refusal_);
  skipped_.push_back({pose_id, "refused by the robot: " + *refusal_});
  NextPose();
}

std::string Campaign::ClockSkewNote() const {
  const std::optional<double> camera = camera_clock_.seconds();
  const std::optional<double> robot = robot_clock_.seconds();
  if (!camera || !robot) return "";
  const double disagreement = *camera - *robot;
  if (std::abs(disagreement) <= options_.pair_tolerance_s) return "";
  return fmt::format(
      " ({}, the robot's joint states {:+.1f} s: the camera's clock is {:.1f} s {} the robot's, "
      "more than the {:.3f} s pairing tolerance: check NTP/chrony on both)",
      DescribeClockOffset("camera status timestamps", *camera), *robot, std::abs(disagreement),
      disagreement > 0 ? "ahead of" : "behind", options_.pair_tolerance_s);
}

void Campaign::WarnOfClockSkew() {
  const std::string note = ClockSkewNote();
  if (note.empty()) return;
  int64_t suppressed = 0;
  if (!clock_warnings_.Allow(bus::WarningThrottle::Clock::now(), &suppressed)) return;
  // The note without its parentheses.
  spdlog::warn("measurements cannot be paired with joint readings: {}",
               note.substr(2, note.size() - 3));
}

std::string Campaign::StaleCameraNote() const {
  const std::optional<double> offset = bus_.stale_clock_offset_s(channels::kCameraStatus);
  if (!offset) return "";
  return fmt::format(
      ": {} dropped as stale: {}, beyond the {:.0f} s the message authentication accepts: "
      "check NTP/chrony on the camera and on this host",
      bus_.stale_messages(channels::kCameraStatus),
      DescribeClockOffset("camera status timestamps", *offset), bus_.max_clock_offset_s());
}

// A key on one end only (messages/README.md#authenticated-messages): each end sees the other's
// messages refused or read unchecked, and says which end lacks the key.
std::string Campaign::KeyMismatchNote() const {
  const int64_t refused = RefusedCameraMessages();
  if (refused > bus_.stale_messages(channels::kCameraStatus)) {
    return fmt::format(
        "the camera answers but its messages are not authenticated with this key ({} dropped): "
        "give h4cam run the same --auth-key as collect, or neither",
        refused);
  }
  if (bus_.unchecked_signed(channels::kCameraStatus) > 0) {
    return "the camera signs its messages (h4cam run --auth-key) and refuses requests without "
           "its key: give collect the same --auth-key, or neither";
  }
  return "";
}

int64_t Campaign::RefusedCameraMessages() const {
  return bus_.auth_failures(channels::kCameraStatus) + bus_.auth_failures(channels::kBoardPose);
}

// Camera messages refused for their key before any was accepted: enough to tell a key on
// this end only from a stray corrupted message (the camera's heartbeat is 1 Hz, so about 3 s).
constexpr int64_t kKeyMismatchEvidence = 3;

void Campaign::StopOnKeyMismatch() const {
  // Refusals while the camera is heard are another campaign's traffic, not ours.
  const int64_t for_their_key =
      RefusedCameraMessages() - bus_.stale_messages(channels::kCameraStatus);
  const bool ours_refused = !camera_heard_ && for_their_key >= kKeyMismatchEvidence;
  const bool signed_unchecked = bus_.unchecked_signed(channels::kCameraStatus) > 0;
  if (!ours_refused && !signed_unchecked) return;
  throw std::runtime_error(
      "the campaign and the camera do not share a key, stopped before "
      "the robot moves: " +
      KeyMismatchNote());
}

void Campaign::NoteWhoWasHeard(Clock::time_point now) {
  if (first_step_ == Clock::time_point{}) first_step_ = now;
  last_step_ = now;
  if (counters_.joint_states != joint_states_at_last_step_) robot_heard_at_ = now;
  // A board pose is heard from the camera too: while it measures a group it may skip a
  // heartbeat or two, and the pose it then sends shows it alive.
  const int64_t camera_messages = camera_statuses_ + counters_.board_poses;
  if (camera_messages != camera_messages_at_last_step_) camera_heard_at_ = now;
  joint_states_at_last_step_ = counters_.joint_states;
  camera_messages_at_last_step_ = camera_messages;
}

std::string Campaign::silent_sides() const {
  auto silence = [this](const std::optional<Clock::time_point>& heard_at, const char* who,
                        const char* channel) -> std::string {
    const double silent_s = Seconds(last_step_ - heard_at.value_or(first_step_));
    if (silent_s <= kSilentAfter_s) return "";
    return fmt::format("the {} is silent (no {} {} {:.0f} s)", who, channel,
                       heard_at ? "for" : "heard in", silent_s);
  };
  const std::string robot = silence(robot_heard_at_, "robot", channels::kJointState);
  const std::string camera = silence(camera_heard_at_, "camera", channels::kCameraStatus);
  if (robot.empty() || camera.empty()) return robot + camera;
  return robot + "; " + camera;
}

void Campaign::LogSilentSides(Clock::time_point now) {
  if (Seconds(now - silence_logged_at_) < kSilentAfter_s) return;
  const std::string silent = silent_sides();
  if (silent.empty()) return;
  spdlog::warn("waiting: {}", silent);
  silence_logged_at_ = now;
}

bool Campaign::Step(Clock::time_point now) {
  if (finished()) return false;
  if (options_.mode == CampaignMode::kPassive) return true;  // handlers do all the work
  NoteWhoWasHeard(now);
  LogSilentSides(now);
  WarnOfClockSkew();
  if (recorded_current_) {
    NextPose();
    return !finished();
  }
  switch (phase_) {
    case Phase::kWaitForDevices:
      WaitForDevices(now);
      break;
    case Phase::kSendTarget:
      SendTarget(now);
      break;
    case Phase::kSettling:
      WaitForSettled(now);
      break;
    case Phase::kSendRequest:
      SendCaptureRequest(now);
      break;
    case Phase::kMeasuring:
      WaitForMeasurement(now);
      break;
  }
  return !finished();
}

// Do not send into the void: a target published before the robot subscribes is lost.
void Campaign::WaitForDevices(Clock::time_point now) {
  if (phase_start_ == Clock::time_point{}) phase_start_ = now;
  StopOnKeyMismatch();
  if (joints_heard_ && camera_heard_) {
    spdlog::info("robot and camera heard; starting");
    phase_ = Phase::kSendTarget;
    return;
  }
  if (Seconds(now - phase_start_) <= options_.settle_timeout_s) return;
  std::string silent = !joints_heard_ ? "no joint state on H4_JOINT_STATE (is the robot "
                                        "controller or h4cal sim-robot running?)"
                                      : "";
  if (!camera_heard_) {
    const std::string stale = StaleCameraNote();
    const std::string key = KeyMismatchNote();
    silent += std::string(silent.empty() ? "" : "; ") +
              (!stale.empty() ? "no camera status accepted on H4_CAMERA_STATUS" + stale
               : !key.empty() ? "no camera status accepted on H4_CAMERA_STATUS: " + key
                              : "no camera status on H4_CAMERA_STATUS (is h4cam running?)");
  }
  throw std::runtime_error(fmt::format("nothing heard for {:.0f} s on {}: {}",
                                       options_.settle_timeout_s, bus_.url(), silent));
}

// Active: the target goes to the robot; guided: the operator is asked to move it.
void Campaign::SendTarget(Clock::time_point now) {
  const PlannedPose& pose = current();
  if (options_.mode == CampaignMode::kActive) {
    if (!PublishTarget(pose, now)) return;
  } else {
    spdlog::info(
        "pose {}: move the robot to X={:.4f} Y={:.4f} Z={:.4f} m theta={:.2f} deg "
        "and let it settle",
        pose.pose_id, pose.x[0], pose.x[1], pose.x[2], DegreesFromRadians(pose.x[3]));
  }
  settled_seen_ = false;
  phase_ = Phase::kSettling;
  phase_start_ = now;
}

// Until the robot reports settled at the target, or refuses it; the target is sent again
// while the robot has not taken it, and the pose retried when it never settles.
void Campaign::WaitForSettled(Clock::time_point now) {
  if (refusal_) {
    SkipRefused();
    return;
  }
  if (settled_seen_) {
    unsettled_in_a_row_.clear();
    phase_ = Phase::kSendRequest;
    return;
  }
  const PlannedPose& pose = current();
  if (options_.mode == CampaignMode::kActive &&
      Seconds(now - target_sent_) > options_.target_resend_s) {
    const std::optional<JointReading> latest = history_.Latest();
    if (!latest || latest->pose_id != pose.pose_id) {
      spdlog::info("pose {}: the robot has not taken the target yet; sending it again",
                   pose.pose_id);
      PublishTarget(pose, now);
    }
  }
  if (Seconds(now - phase_start_) > options_.settle_timeout_s) RetryUnsettled(now);
}

void Campaign::SendCaptureRequest(Clock::time_point now) {
  h4msgs::capture_request_t request{};
  request.utime = NowUtime();
  request.pose_id = current().pose_id;
  request.frame_count = options_.frame_count;
  bus_.Publish(channels::kCaptureRequest, request);
  failed_attempt_.reset();
  phase_ = Phase::kMeasuring;
  phase_start_ = now;
}

// Until the camera's board pose is recorded (by the handler); a failed measurement or
// none within the capture timeout retries. An active campaign retries from the target: the
// robot may have left it (one stray robot_target_t made it hold, not settled, and retrying
// only the capture then cost the pose); sending the same target to a robot still settled
// there changes nothing.
void Campaign::WaitForMeasurement(Clock::time_point now) {
  const Phase retry_from =
      options_.mode == CampaignMode::kActive ? Phase::kSendTarget : Phase::kSendRequest;
  if (failed_attempt_) {
    Retry(retry_from, *failed_attempt_, now);
  } else if (Seconds(now - phase_start_) > options_.capture_timeout_s) {
    const std::string key = KeyMismatchNote();
    const std::string hint = !key.empty()    ? " (" + key + ")"
                             : camera_heard_ ? ""
                                             : " (no camera status heard at all: is h4cam "
                                               "running?)";
    Retry(retry_from,
          fmt::format("no measurement after {:.1f} s{}", options_.capture_timeout_s, hint), now);
  }
}

std::string Campaign::waiting_for() const {
  if (finished()) return "done";
  if (options_.mode == CampaignMode::kPassive) return "listening";
  const std::string now_waiting = phase_waiting_for();
  const std::string silent = silent_sides();
  if (silent.empty() || phase_ == Phase::kWaitForDevices) return now_waiting;
  return now_waiting + "; " + silent;
}

std::string Campaign::phase_waiting_for() const {
  const int64_t id = current().pose_id;
  const std::string attempt =
      attempt_ > 0 ? fmt::format(" (attempt {}/{})", attempt_ + 1, options_.retries + 1) : "";
  switch (phase_) {
    case Phase::kWaitForDevices: {
      const std::string robot = joints_heard_ ? "" : "the robot (H4_JOINT_STATE)";
      const std::string camera = camera_heard_ ? "" : "the camera (H4_CAMERA_STATUS)";
      return "waiting to hear " + robot + (robot.empty() || camera.empty() ? "" : " and ") + camera;
    }
    case Phase::kSendTarget:
      return fmt::format("pose {}: sending target{}", id, attempt);
    case Phase::kSettling:
      return fmt::format("pose {}: waiting for the robot to settle{}", id, attempt);
    case Phase::kSendRequest:
      return fmt::format("pose {}: requesting a measurement", id);
    case Phase::kMeasuring:
      return fmt::format("pose {}: camera measuring{}", id, attempt);
  }
  return "";
}

}  // namespace h4::host
