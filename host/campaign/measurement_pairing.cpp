// Message checks and the pairing rule; see measurement_pairing.h.
#include "host/campaign/measurement_pairing.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/geometry/covariance_check.h"
#include "common/geometry/rotation.h"
#include "messages/board_pose_status.h"

namespace h4::host {
namespace {

bool AllFinite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

}  // namespace

MessageProblem CheckJointState(const h4msgs::joint_state_t& msg, JointReading* reading,
                               std::string* why) {
  if (msg.joint_count != 4 || msg.position.size() != 4) {
    *why = fmt::format("joint state with {} joints (an H4 has 4)", msg.joint_count);
    return MessageProblem::kWrongJointCount;
  }
  if (!AllFinite(msg.position.data(), 4) || msg.utime <= 0) {
    *why = "joint state with a non-finite position or a non-positive utime";
    return MessageProblem::kImpossibleValues;
  }
  // The dataset reader's bound (dataset_csv.h kMaxJointReading): a row the campaign wrote
  // with a larger reading would make its own dataset unreadable.
  for (int i = 0; i < 4; ++i) {
    if (!IsJointReadingInBounds(msg.position[i])) {
      *why = fmt::format("joint state with q{} = {:g} rad, beyond one turn (|q| <= 2 pi rad)",
                         i + 1, msg.position[i]);
      return MessageProblem::kImpossibleValues;
    }
  }
  reading->utime = msg.utime;
  reading->pose_id = msg.pose_id;
  for (int i = 0; i < 4; ++i) reading->q[i] = msg.position[i];
  reading->settled = msg.settled;
  return MessageProblem::kNone;
}

MessageProblem CheckBoardPose(const h4msgs::board_pose_t& msg, std::string* why) {
  if (!AllFinite(msg.translation, 3) || !AllFinite(msg.quaternion, 4) ||
      !AllFinite(msg.covariance, 36)) {
    *why = fmt::format("board pose {} holds a non-finite number", msg.pose_id);
    return MessageProblem::kImpossibleValues;
  }
  const double z = msg.translation[2];
  const double distance = std::hypot(msg.translation[0], msg.translation[1], z);
  if (!(z > 0.0) || distance > 20.0) {
    *why = fmt::format(
        "board pose {}: the board at ({:.3f}, {:.3f}, {:.3f}) m is not in front "
        "of the camera within 20 m",
        msg.pose_id, msg.translation[0], msg.translation[1], z);
    return MessageProblem::kImpossibleValues;
  }
  Eigen::Matrix3d R;
  if (!RotationFromQuaternion(msg.quaternion[0], msg.quaternion[1], msg.quaternion[2],
                              msg.quaternion[3], &R)) {
    *why = fmt::format(
        "board pose {}: quaternion is not unit (norm {:.6f})", msg.pose_id,
        std::sqrt(msg.quaternion[0] * msg.quaternion[0] + msg.quaternion[1] * msg.quaternion[1] +
                  msg.quaternion[2] * msg.quaternion[2] + msg.quaternion[3] * msg.quaternion[3]));
    return MessageProblem::kImpossibleValues;
  }
  for (int i = 0; i < 6; ++i) {
    if (!(msg.covariance[i * 6 + i] > 0.0)) {
      *why = fmt::format("board pose {}: covariance diagonal element {} is not positive",
                         msg.pose_id, i);
      return MessageProblem::kImpossibleValues;
    }
  }
  if (msg.utime <= 0) {
    *why = fmt::format("board pose {}: utime {} is not a time", msg.pose_id, msg.utime);
    return MessageProblem::kImpossibleValues;
  }
  for (int i = 0; i < 6; ++i) {
    const double sigma = std::sqrt(msg.covariance[i * 6 + i]);
    const SigmaBounds& bounds = i < 3 ? kSigmaTBounds : kSigmaRBounds;
    if (sigma < bounds.min || sigma > bounds.max) {
      *why = fmt::format(
          "board pose {}: covariance diagonal element {} ({:g}) is a standard "
          "deviation of {:g} {}, outside [{:g}, {:g}]: not a camera measurement",
          msg.pose_id, i, msg.covariance[i * 6 + i], sigma, i < 3 ? "m" : "rad", bounds.min,
          bounds.max);
      return MessageProblem::kNonPhysicalCovariance;
    }
  }
  // The diagonal alone passes a symmetric matrix that is no covariance (issue 42): the
  // identification would weigh the pose by its inverse.
  const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> C(msg.covariance);
  if (const std::string problem = CovarianceProblem(C); !problem.empty()) {
    *why = fmt::format("board pose {}: the covariance is {}", msg.pose_id, problem);
    return MessageProblem::kNonPhysicalCovariance;
  }
  return MessageProblem::kNone;
}

std::string BoardPoseStatusName(int8_t status) {
  const std::optional<BoardPoseStatus> known = BoardPoseStatusFromWire(status);
  return known ? ToString(*known) : fmt::format("unknown status {}", static_cast<int>(status));
}

namespace {

void PushBounded(std::deque<JointReading>* readings, const JointReading& reading, size_t capacity) {
  readings->push_back(reading);
  while (readings->size() > capacity) readings->pop_front();
}

/// The settled reading of `readings` nearest to `utime` within `tolerance_us`.
std::optional<JointReading> Nearest(const std::deque<JointReading>& readings,
                                    std::optional<int64_t> pose_id, int64_t utime,
                                    int64_t tolerance_us) {
  std::optional<JointReading> best;
  int64_t best_gap = std::numeric_limits<int64_t>::max();
  for (const JointReading& r : readings) {
    if (!r.settled || (pose_id && r.pose_id != *pose_id)) continue;
    // Both utimes are positive (CheckJointState, CheckBoardPose): no overflow.
    const int64_t gap = r.utime > utime ? r.utime - utime : utime - r.utime;
    // Ties go to the earlier reading: the decision depends only on what was received.
    if (gap <= tolerance_us && gap < best_gap) {
      best = r;
      best_gap = gap;
    }
  }
  return best;
}

}  // namespace

void JointHistory::Add(const JointReading& reading) {
  PushBounded(&readings_, reading, capacity_);
  if (!reading.settled) return;
  PushBounded(&settled_, reading, capacity_);
  const auto tracked = tracked_.find(reading.pose_id);
  if (tracked != tracked_.end()) PushBounded(&tracked->second, reading, per_pose_capacity_);
}

void JointHistory::Track(int64_t pose_id) { tracked_.try_emplace(pose_id); }

void JointHistory::Forget(int64_t pose_id) { tracked_.erase(pose_id); }

std::optional<JointReading> JointHistory::FindSettled(std::optional<int64_t> pose_id, int64_t utime,
                                                      int64_t tolerance_us) const {
  if (pose_id) {
    const auto tracked = tracked_.find(*pose_id);
    if (tracked != tracked_.end()) return Nearest(tracked->second, pose_id, utime, tolerance_us);
  }
  return Nearest(settled_, pose_id, utime, tolerance_us);
}

void JointHistory::Clear() {
  readings_.clear();
  settled_.clear();
  for (auto& [pose_id, readings] : tracked_) readings.clear();
}

std::optional<JointReading> JointHistory::Latest() const {
  if (readings_.empty()) return std::nullopt;
  return readings_.back();
}

DatasetRow MakeDatasetRow(const h4msgs::board_pose_t& measurement, const JointReading& joints) {
  DatasetRow row;
  row.pose_id = measurement.pose_id;
  row.utime = measurement.utime;
  row.q = joints.q;
  row.X_CT = RigidTransform::FromTranslationQuaternion(
      Eigen::Vector3d(measurement.translation[0], measurement.translation[1],
                      measurement.translation[2]),
      Eigen::Vector4d(measurement.quaternion[0], measurement.quaternion[1],
                      measurement.quaternion[2], measurement.quaternion[3]));
  const double* c = measurement.covariance;
  row.sigma_t = std::sqrt((c[0] + c[7] + c[14]) / 3.0);
  row.sigma_r = std::sqrt((c[21] + c[28] + c[35]) / 3.0);
  return row;
}

}  // namespace h4::host
