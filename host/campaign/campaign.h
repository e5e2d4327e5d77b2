// `h4cal collect`'s campaign (issue "Live system", item 3; the paper's protocol, section
// IV.A): for each planned pose, send the robot target, wait until the robot has settled,
// request an averaged camera measurement, pair it with the joint reading of the same moment
// and append the row to the dataset durably. Retries measurements flagged moved / partial /
// no board, unpaired ones and timeouts (active mode: from the target, sent again, and the
// robot settled again), then skips and lists the pose. A target the robot refuses
// (H4_TARGET_STATUS) is skipped at once with the robot's reason. Three modes:
//   active  - drives the robot (H4_ROBOT_TARGET) and the camera (H4_CAPTURE_REQUEST);
//   manual  - the operator moves the robot; a pose is taken when the robot has moved and
//             settled again; only capture requests are sent;
//   passive - sends nothing, pairs what it hears (a live lcm-logplayer replay, or a log
//             read through LCM's file:// provider), by the same rule as the live run.
// The campaign is a state machine over one bus: Step() is called after bus.Handle(), so a
// test can run it beside other nodes on the in-process memq:// provider.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <h4msgs/board_corners_t.hpp>
#include <h4msgs/board_pose_t.hpp>
#include <h4msgs/camera_status_t.hpp>
#include <h4msgs/joint_state_t.hpp>
#include <h4msgs/target_status_t.hpp>

#include "host/campaign/clock_offset.h"
#include "host/campaign/corners_journal.h"
#include "host/campaign/dataset_journal.h"
#include "host/campaign/measurement_pairing.h"
#include "host/campaign/stale_filter.h"
#include "host/kinematics/pose_plan.h"
#include "messages/bus/lcm_bus.h"
#include "messages/bus/warning_throttle.h"

namespace h4::host {

/// Named by ModeName, in this order (campaign.cpp).
enum class CampaignMode { kActive, kManual, kPassive };

struct CampaignOptions {
  CampaignMode mode = CampaignMode::kActive;
  int frame_count = 0;              ///< frames per measurement; 0: the camera's default (10)
  double settle_timeout_s = 30.0;   ///< robot target to settled
  double capture_timeout_s = 10.0;  ///< capture request to board pose
  int retries = 2;                  ///< extra attempts per pose before it is skipped
  /// Active mode: after this many poses in a row skipped because the robot never settled,
  /// the campaign stops (Step() throws, naming them) instead of spending the settle timeout
  /// on every pose left: a robot that never reports settled would otherwise keep the
  /// campaign waiting for hours. 0: never stop, skip every such pose.
  int max_unsettled_in_a_row = 3;
  double pair_tolerance_s = 0.2;  ///< max |utime(joints) - utime(measurement)|
  /// Active mode: a target the robot has not acknowledged (its joint states still carry
  /// another pose id) after this long is sent again (a lost datagram, a robot started late).
  double target_resend_s = 1.0;
  /// Active mode: when set, each planned pose is sent as joint targets computed by this
  /// control law (e.g. Model 12 inverse kinematics of given parameters, the paper's square
  /// experiment) instead of as a pose for the robot's own controller. An empty result means
  /// unreachable: the pose is skipped with `why`.
  using ControlLaw = std::function<std::optional<JointVector>(const EePose& x_B, std::string* why)>;
  ControlLaw control_law;
  /// Active mode: poses known before the robot moves to be out of its reach (pose id ->
  /// why; `collect --robot`'s check of the plan): skipped with the reason, no target sent.
  std::map<int64_t, std::string> unreachable;
};

struct SkippedPose {
  int64_t pose_id = 0;
  std::string reason;
  bool not_sent = false;  ///< out of reach by the plan's check (CampaignOptions::unreachable)
};

/// Messages the campaign did not use, and why (LCM hygiene: counted and logged, never fatal).
struct CampaignCounters {
  int64_t joint_states = 0;
  int64_t board_poses = 0;
  int64_t impossible_values = 0;        ///< messages with numbers no robot or camera can produce
  int64_t nonphysical_covariances = 0;  ///< measurements whose sigmas no camera reaches
  int64_t unexpected_pose_ids = 0;      ///< measurements of a pose not planned or not awaited
  int64_t duplicates = 0;               ///< measurements of a pose already recorded
  int64_t stale_joint_states = 0;       ///< joint states far older than the robot's latest
  int64_t unpaired = 0;                 ///< measurements with no settled joint reading in tolerance
  int64_t retries = 0;                  ///< attempts repeated (timeouts, moved, partial, ...)
  int64_t board_corners = 0;            ///< board_corners_t messages heard
  int64_t unusable_corners = 0;  ///< board_corners_t not written (impossible values, no pose)
};

class Campaign {
 public:
  using Clock = std::chrono::steady_clock;

  /// Subscribes to H4_JOINT_STATE, H4_TARGET_STATUS, H4_BOARD_POSE and H4_CAMERA_STATUS on
  /// `bus`. Poses of `plan` already in `journal` (a resumed campaign) are not measured again.
  Campaign(bus::LcmBus& bus, PosePlan plan, DatasetJournal& journal, CampaignOptions options);
  /// Also subscribes to H4_BOARD_CORNERS and appends the corners of each pose recorded by
  /// this campaign to `corners` (paired by pose id and the pose's utime, whichever comes
  /// first). A camera that sends none (older firmware, old logs) costs nothing but the
  /// corners: poses_without_corners() lists them.
  Campaign(bus::LcmBus& bus, PosePlan plan, DatasetJournal& journal, CornersJournal& corners,
           CampaignOptions options);

  /// Sends what is due and handles timeouts at time `now`; false once every planned pose
  /// is recorded or skipped. Active and manual campaigns first wait (up to the settle
  /// timeout) until the robot's joint states and the camera's heartbeat are heard, and
  /// throw std::runtime_error naming what is silent when they are not.
  bool Step(Clock::time_point now);
  bool finished() const { return next_ >= pending_.size(); }

  /// Planned poses, and those recorded or skipped so far (including resumed ones).
  int planned_count() const { return static_cast<int>(plan_.size()); }
  int done_count() const;
  /// What the campaign waits for now, for the progress bar; names the side (robot or
  /// camera) that has been silent for longer than kSilentAfter_s, or never heard.
  std::string waiting_for() const;
  /// "" when both sides were heard within kSilentAfter_s of the last Step(); else which is
  /// silent and on which channel, e.g. "the robot is silent (no H4_JOINT_STATE for 4 s)".
  std::string silent_sides() const;
  /// A side unheard for this long is called silent: the camera's heartbeat comes every
  /// second (firmware/packaging/h4cam.yaml), a robot's joint states at 100 Hz.
  static constexpr double kSilentAfter_s = 3.0;
  const std::vector<SkippedPose>& skipped() const { return skipped_; }
  const CampaignCounters& counters() const { return counters_; }
  /// Poses recorded by this campaign whose corners have not arrived (none without a
  /// corners journal).
  std::vector<int64_t> poses_without_corners() const;

 private:
  enum class Phase { kWaitForDevices, kSendTarget, kSettling, kSendRequest, kMeasuring };

  void OnJointState(const h4msgs::joint_state_t& msg);
  /// Active mode: a refusal of the awaited target ends its wait (acted on by Step()).
  void OnTargetStatus(const h4msgs::target_status_t& msg);
  void OnCameraStatus(const h4msgs::camera_status_t& msg);
  void OnBoardPose(const h4msgs::board_pose_t& msg);
  void OnBoardCorners(const h4msgs::board_corners_t& msg);
  /// After pose `pose_id` (measured at `utime`) is recorded: its corners, if already here.
  void PairCornersOf(int64_t pose_id, int64_t utime);
  /// Appends a message's corners; false (counted, logged) when a value is impossible.
  bool AppendCorners(const h4msgs::board_corners_t& msg);
  /// Pairs and records an OK measurement of `pose_id`; false (with `why`) when it cannot.
  bool Record(const h4msgs::board_pose_t& msg, std::optional<int64_t> joint_pose_id,
              std::string* why);
  /// A failed attempt at the current pose: retry from `phase`, or skip when none is left.
  void Retry(Phase phase, const std::string& why, Clock::time_point now);
  /// The robot did not settle at the current pose in time: Retry, and stop the campaign
  /// (throw) once max_unsettled_in_a_row poses in a row were skipped so.
  void RetryUnsettled(Clock::time_point now);
  /// The robot refused the current target: skips the pose with its reason, no retry (the
  /// same target would be refused again).
  void SkipRefused();
  /// One Step() in each phase of the state machine.
  void WaitForDevices(Clock::time_point now);
  void SendTarget(Clock::time_point now);
  void WaitForSettled(Clock::time_point now);
  void SendCaptureRequest(Clock::time_point now);
  void WaitForMeasurement(Clock::time_point now);
  /// Sends the target of `pose`; false (pose skipped) when the control law cannot reach it.
  bool PublishTarget(const PlannedPose& pose, Clock::time_point now);
  void NextPose();
  /// waiting_for() of the phase alone.
  std::string phase_waiting_for() const;
  /// Notes, at each Step(), whether the robot and the camera were heard since the last one.
  void NoteWhoWasHeard(Clock::time_point now);
  /// Logs which side is silent, at most every kSilentAfter_s while it stays so.
  void LogSilentSides(Clock::time_point now);
  bool IsPlanned(int64_t pose_id) const;
  /// Logs `text` through `throttle` (at most once a second, as the bus does: a flood of bad
  /// messages must not become a flood of log lines), saying how many were held back.
  static void WarnThrottled(bus::WarningThrottle& throttle, const std::string& text);
  /// " (camera status timestamps are 20.0 s ahead of ...: check NTP/chrony)" when the
  /// camera's and the robot's clocks disagree by more than the pairing tolerance (their
  /// utimes cannot pair then); "" otherwise.
  std::string ClockSkewNote() const;
  /// Warns, at most every 10 s (clock_warnings_), while ClockSkewNote() names a disagreement.
  void WarnOfClockSkew();
  /// Why no camera status was heard, when the bus dropped them as stale: their clock.
  std::string StaleCameraNote() const;
  std::string KeyMismatchNote() const;
  /// Camera statuses and board poses the bus refused (stale ones included).
  int64_t RefusedCameraMessages() const;
  /// Throws, naming the fix, when the campaign and the camera do not share a key, before
  /// the robot moves: the camera would refuse every request, or every answer be dropped.
  void StopOnKeyMismatch() const;
  const PlannedPose& current() const { return plan_[pending_[next_]]; }

  bus::LcmBus& bus_;
  PosePlan plan_;
  DatasetJournal& journal_;
  CampaignOptions options_;

  std::vector<size_t> pending_;  ///< indices into plan_ of the poses to measure, in order
  size_t next_ = 0;              ///< index into pending_ of the pose in progress
  Phase phase_ = Phase::kWaitForDevices;
  Clock::time_point target_sent_{};  ///< when the current target was last published
  int attempt_ = 0;
  Clock::time_point phase_start_{};
  bool settled_seen_ = false;                  ///< the robot reported settled at the current pose
  bool moved_since_capture_ = false;           ///< manual mode: the operator moved the robot
  std::optional<std::string> failed_attempt_;  ///< set by a handler, acted on by Step()
  std::optional<std::string> refusal_;         ///< the robot refused the current target: why
  bool recorded_current_ = false;              ///< set by a handler, acted on by Step()
  bool camera_heard_ = false;
  bool joints_heard_ = false;
  int64_t camera_statuses_ = 0;               ///< camera heartbeats heard
  int64_t joint_states_at_last_step_ = 0;     ///< counters_.joint_states at the last Step()
  int64_t camera_messages_at_last_step_ = 0;  ///< heartbeats + board poses at the last Step()
  std::optional<Clock::time_point> robot_heard_at_, camera_heard_at_;  ///< by Step()'s clock
  Clock::time_point first_step_{}, last_step_{}, silence_logged_at_{};
  std::vector<int64_t> unsettled_in_a_row_;  ///< poses skipped as not settled since the last
                                             ///< pose that settled

  CornersJournal* corners_ = nullptr;
  /// Recorded poses awaiting their corners: pose id -> the board pose's utime.
  std::map<int64_t, int64_t> awaiting_corners_;
  /// Corners heard before their pose was recorded (reordered, or the pose not yet paired),
  /// the newest per pose id, at most kEarlyCornersKept.
  std::map<int64_t, h4msgs::board_corners_t> early_corners_;
  static constexpr size_t kEarlyCornersKept = 8;

  JointHistory history_;
  std::vector<SkippedPose> skipped_;
  CampaignCounters counters_;

  /// The camera's and the robot's clocks against this host's, from the utimes of their
  /// heartbeats and joint states at arrival (active and manual modes: a replayed log's are
  /// old by definition).
  ClockOffset camera_clock_, robot_clock_;
  StaleMessageFilter robot_staleness_;  ///< joint states far behind the robot's latest
  /// One per kind of warning a message can cause.
  bus::WarningThrottle joint_state_warnings_, unexpected_pose_warnings_, measurement_warnings_,
      corners_warnings_;
  bus::WarningThrottle clock_warnings_{std::chrono::seconds(10)};
};

}  // namespace h4::host
