// Pairing a camera measurement with the joint reading of the same moment (issue "Live
// system", item 3): the campaign's core rule, kept free of the bus so that the live run,
// the passive listener and the log replay apply exactly the same decision to the same
// sequence of messages (and so rebuild the same dataset rows).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>

#include <h4msgs/board_pose_t.hpp>
#include <h4msgs/joint_state_t.hpp>

#include "host/formats/dataset_csv.h"

namespace h4::host {

/// One encoder reading as received on H4_JOINT_STATE.
struct JointReading {
  int64_t utime = 0;
  int64_t pose_id = -1;
  std::array<double, 4> q{};
  bool settled = false;
};

/// Why a message was not used; kNone when it is fine.
enum class MessageProblem {
  kNone,
  kImpossibleValues,  ///< non-finite, non-unit quaternion, board behind the camera, ...
  kWrongJointCount,   ///< an H4 has 4 joints
  /// a positive covariance whose standard deviations no camera measures (outside the
  /// dataset's kSigmaTBounds / kSigmaRBounds: a 1e-320 variance would give the dataset a
  /// sigma of ~1e-160, and the identification weights of 1e320)
  kNonPhysicalCovariance,
};

/// Bounds on each standard deviation of a board pose's covariance diagonal: the dataset's
/// own (kSigmaTBounds for the translation, m; kSigmaRBounds for the rotation, rad), so that
/// every row the campaign records loads back. No camera measures a board to a nanometre:
/// such a sigma comes from a fit with next to no residual and would weigh its row 1e18
/// times more than a real one. The floor stays far below what the fit reports for rendered
/// images (the live_campaign test's camera: sigma_t from 1.1e-6 m, sigma_r from 7.2e-6 rad).

/// Checks a joint state and converts it; `why` says what is wrong.
MessageProblem CheckJointState(const h4msgs::joint_state_t& msg, JointReading* reading,
                               std::string* why);

/// Checks the numbers of a board pose whose status is OK: finite translation with the board
/// in front of the camera (z > 0) and within 20 m, unit quaternion (1e-3), finite covariance
/// with a positive diagonal (else kImpossibleValues) whose square roots lie within
/// the dataset's kSigmaTBounds / kSigmaRBounds (else kNonPhysicalCovariance). Statuses
/// other than OK are not "impossible": the caller retries them.
MessageProblem CheckBoardPose(const h4msgs::board_pose_t& msg, std::string* why);

/// A short name for a board pose status ("ok", "no board", "moved", "partial",
/// "camera error", or "unknown status N").
std::string BoardPoseStatusName(int8_t status);

/// The recent joint readings, oldest first, bounded. The settled readings of the pose ids
/// the owner tracks (the planned poses not yet recorded) are kept apart, per pose id, so that
/// a flood of other readings (another publisher, a robot streaming while it moves) cannot
/// push out the readings a measurement of a tracked pose is paired with.
class JointHistory {
 public:
  /// `capacity`: readings kept for Latest() and for pose ids not tracked (a few seconds at
  /// 100 Hz); `per_pose_capacity`: settled readings kept per tracked pose id (10 s of a
  /// 1 kHz controller; a measurement is stamped with its first frame, a second or two of
  /// averaging before it arrives).
  explicit JointHistory(size_t capacity = 2000, size_t per_pose_capacity = 10000)
      : capacity_(capacity), per_pose_capacity_(per_pose_capacity) {}
  void Add(const JointReading& reading);
  /// Keeps the settled readings of `pose_id` apart from now on / no longer.
  void Track(int64_t pose_id);
  void Forget(int64_t pose_id);
  /// The settled reading nearest in time to `utime` within `tolerance_us`, among those of
  /// `pose_id` (or of any pose id when `pose_id` is nullopt: a robot driven by hand).
  std::optional<JointReading> FindSettled(std::optional<int64_t> pose_id, int64_t utime,
                                          int64_t tolerance_us) const;
  /// The newest reading, if any.
  std::optional<JointReading> Latest() const;
  void Clear();

 private:
  size_t capacity_;
  size_t per_pose_capacity_;
  std::deque<JointReading> readings_;                    ///< every reading
  std::deque<JointReading> settled_;                     ///< settled readings of any pose id
  std::map<int64_t, std::deque<JointReading>> tracked_;  ///< settled, per tracked pose id
};

/// The dataset row of a measurement and its joint reading: utime and X_CT from the camera,
/// q from the encoders, sigma_t / sigma_r from the covariance's translation and rotation
/// blocks (root of the mean diagonal: one std per axis, as common/formats/README.md's columns
/// mean).
DatasetRow MakeDatasetRow(const h4msgs::board_pose_t& measurement, const JointReading& joints);

}  // namespace h4::host
