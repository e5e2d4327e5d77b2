// The simulated H4 controller; see simulated_controller.h.
#include "host/campaign/simulated_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/geometry/rotation.h"
#include "common/text/enum_names.h"
#include "common/text/invalid_reason.h"
#include "common/units.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"

namespace h4::host {
namespace {

// Two joint vectors closer than this (wrapped, rad) are the same target: far below the
// encoder noise, so a resent target compares equal after any round trip through a message.
constexpr double kSameTargetTolerance = 1e-12;

JointVector WrappedDifference(const JointVector& a, const JointVector& b) {
  JointVector d;
  for (int i = 0; i < 4; ++i) d[i] = WrapAngle(a[i] - b[i]);
  return d;
}

// In degrees, as collect --dry-run and --joint-range-deg speak of joints (issue 43 point 8).
std::string FormatJoints(const JointVector& q) {
  return fmt::format("({:.2f}, {:.2f}, {:.2f}, {:.2f}) deg", DegreesFromRadians(q[0]),
                     DegreesFromRadians(q[1]), DegreesFromRadians(q[2]), DegreesFromRadians(q[3]));
}

}  // namespace

bool SimulatedControllerOptions::IsValid(std::string* why) const {
  if (!(std::isfinite(joint_speed) && joint_speed > 0.0)) {
    return Invalid(why, fmt::format("joint speed must be positive, got {:f} rad/s", joint_speed));
  }
  if (!(std::isfinite(settle_time) && settle_time >= 0.0)) {
    return Invalid(why, fmt::format("settle time must be >= 0, got {:f} s", settle_time));
  }
  if (!(std::isfinite(sigma_q) && sigma_q >= 0.0)) {
    return Invalid(why, fmt::format("encoder noise must be >= 0, got {:f} rad", sigma_q));
  }
  if (!(std::isfinite(joint_range) && joint_range > 0.0)) {
    return Invalid(why, fmt::format("joint range must be positive, got {:f} rad", joint_range));
  }
  if (joint_limits && !(joint_limits->allFinite() && (*joint_limits)[0] < (*joint_limits)[1])) {
    return Invalid(why, "joint limits must be finite with MIN < MAX");
  }
  if (!home.allFinite()) return Invalid(why, "home pose is not finite");
  return true;
}

constexpr EnumNames<TargetStatus, TargetStatus::kInvalid> kTargetStatusNames = {
    "accepted", "unreachable", "outside joint limits", "invalid"};

const char* ToString(TargetStatus status) { return kTargetStatusNames.NameOf(status, "invalid"); }

SimulatedController::SimulatedController(const SimulatedRobot& truth,
                                         const Model12Parameters& apriori,
                                         const Assembly& apriori_assembly,
                                         const SimulatedControllerOptions& options)
    : truth_(truth),
      true_model_(truth.MakeModel()),
      apriori_model_(std::make_unique<Model12>(apriori, apriori_assembly)),
      X_ModelB_(truth.X_ModelB()),
      options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument("simulated controller: " + why);
  const RigidTransform X_BE_home = TransformFromEePose(options_.home);
  const EePose x_model = EePoseFromTransform(X_ModelB_ * X_BE_home);
  const IkResult ik = true_model_->InverseKinematics(x_model);
  if (!ik.ok()) {
    throw std::invalid_argument(fmt::format(
        "simulated controller: the true robot cannot reach the home pose ({:.3f}, {:.3f}, "
        "{:.3f}) m, theta {:.3f} rad",
        options_.home[0], options_.home[1], options_.home[2], options_.home[3]));
  }
  q_home_ = ik.q;
  q_ = ik.q;
  q_target_ = ik.q;
  q_from_ = ik.q;
  X_BE_ = X_BE_home;
  x_model_ = x_model;
  x_home_model_ = x_model;
  x_from_model_ = x_model;
  x_target_model_ = x_model;
  // At rest at home from the start: settled with pose id -1.
  time_at_target_ = options_.settle_time;
}

SimulatedController::~SimulatedController() = default;

TargetResult SimulatedController::SetPoseTarget(int64_t pose_id, const EePose& x_B) {
  if (!x_B.allFinite()) {
    return Refuse(pose_id, TargetStatus::kInvalid, "pose target is not finite");
  }
  const IkResult ik = apriori_model_->InverseKinematics(x_B);
  if (!ik.ok()) {
    return Refuse(pose_id, TargetStatus::kUnreachable,
                  fmt::format("pose ({:.4f}, {:.4f}, {:.4f}) m, theta {:.4f} rad is out of reach "
                              "of the a priori model (leg {} has no inverse kinematics)",
                              x_B[0], x_B[1], x_B[2], x_B[3], ik.UnreachableLegNumbers()));
  }
  // The true robot at these joints is millimetres from the commanded pose: a start on its
  // branch.
  return SetTarget(pose_id, ik.q, EePoseFromTransform(X_ModelB_ * TransformFromEePose(x_B)));
}

TargetResult SimulatedController::SetJointTarget(int64_t pose_id, const JointVector& q_in) {
  return SetTarget(pose_id, q_in, std::nullopt);
}

TargetResult SimulatedController::SetTarget(int64_t pose_id, const JointVector& q_in,
                                            const std::optional<EePose>& seed_model) {
  if (!q_in.allFinite()) {
    return Refuse(pose_id, TargetStatus::kInvalid, "joint target is not finite");
  }
  JointVector q;
  for (int i = 0; i < 4; ++i) q[i] = WrapAngle(q_in[i]);
  const JointVector from_home = WrappedDifference(q, q_home_);
  for (int i = 0; i < 4; ++i) {
    if (std::abs(from_home[i]) > options_.joint_range) {
      return Refuse(
          pose_id, TargetStatus::kOutsideLimits,
          fmt::format("joint {} target {:.2f} deg is {:.2f} deg from its home {:.2f} "
                      "deg, beyond the joint range {:.2f} deg",
                      i + 1, DegreesFromRadians(q[i]), DegreesFromRadians(from_home[i]),
                      DegreesFromRadians(q_home_[i]), DegreesFromRadians(options_.joint_range)));
    }
    if (options_.joint_limits &&
        (q[i] < (*options_.joint_limits)[0] || q[i] > (*options_.joint_limits)[1])) {
      return Refuse(pose_id, TargetStatus::kOutsideLimits,
                    fmt::format("joint {} target {:.1f} deg, outside the joint range "
                                "{:.1f}..{:.1f} deg",
                                i + 1, DegreesFromRadians(q[i]),
                                DegreesFromRadians((*options_.joint_limits)[0]),
                                DegreesFromRadians((*options_.joint_limits)[1])));
    }
  }
  EePose x_target_model;
  // The commanded pose is the nearer start; where the a priori robot misses it by too much
  // for Newton's method (near the theta singularity, tenths of a radian), home followed
  // along the joints is the start on the branch.
  const bool solved = (seed_model && TruePoseFrom(q, *seed_model, &x_target_model)) ||
                      TruePoseFromHome(q, &x_target_model);
  if (!solved) {
    return Refuse(pose_id, TargetStatus::kUnreachable,
                  "the true robot has no pose at joints " + FormatJoints(q));
  }
  return Accept(pose_id, q, x_target_model);
}

TargetResult SimulatedController::RejectTarget(int64_t pose_id, const std::string& reason) {
  return Refuse(pose_id, TargetStatus::kInvalid, reason);
}

TargetResult SimulatedController::Accept(int64_t pose_id, const JointVector& q,
                                         const EePose& x_target_model) {
  pose_id_ = pose_id;
  const bool same_target =
      !refused_ && WrappedDifference(q, q_target_).cwiseAbs().maxCoeff() <= kSameTargetTolerance;
  if (!same_target) {
    q_from_ = q_;
    x_from_model_ = x_model_;
    q_target_ = q;
    x_target_model_ = x_target_model;
    time_at_target_ = 0.0;
  }
  refused_ = false;
  TargetResult result;
  result.status = TargetStatus::kAccepted;
  result.q_target = q_target_;
  return result;
}

TargetResult SimulatedController::Refuse(int64_t pose_id, TargetStatus status,
                                         const std::string& reason) {
  // Hold where it is; the campaign sees this pose id never settle and skips it.
  pose_id_ = pose_id;
  refused_ = true;
  q_target_ = q_;
  q_from_ = q_;
  x_from_model_ = x_model_;
  x_target_model_ = x_model_;
  time_at_target_ = 0.0;
  TargetResult result;
  result.status = status;
  result.reason = reason;
  return result;
}

void SimulatedController::Step(double dt_s) {
  if (!std::isfinite(dt_s) || dt_s <= 0.0) return;
  const JointVector delta = WrappedDifference(q_target_, q_);
  const double distance = delta.cwiseAbs().maxCoeff();
  if (distance == 0.0) {
    time_at_target_ += dt_s;
    return;
  }
  // Straight line in joint space at joint_speed for the joint with the farthest to go.
  const double travel = options_.joint_speed * dt_s;
  if (travel >= distance) {
    q_ = q_target_;
    time_at_target_ = dt_s - distance / options_.joint_speed;
    SetCurrentPose(x_target_model_);  // solved on its branch when the target was accepted
    return;
  }
  for (int i = 0; i < 4; ++i) q_[i] = WrapAngle(q_[i] + delta[i] * (travel / distance));
  // Start from the pose as far between the motion's ends as the joints are.
  const double total = WrappedDifference(q_target_, q_from_).cwiseAbs().maxCoeff();
  const double done = total > 0.0 ? 1.0 - (distance - travel) / total : 1.0;
  EePose seed = x_from_model_ + done * (x_target_model_ - x_from_model_);
  seed[3] = x_from_model_[3] + done * WrapAngle(x_target_model_[3] - x_from_model_[3]);
  EePose x_model;
  if (TruePoseFrom(q_, seed, &x_model)) {
    SetCurrentPose(x_model);
  } else {
    // Between two assemblable targets the straight joint path should stay assemblable; if
    // not, the board pose freezes at the last solved pose rather than becoming NaN.
    ++fk_failures_;
  }
}

void SimulatedController::SetCurrentPose(const EePose& x_model) {
  x_model_ = x_model;
  X_BE_ = X_ModelB_.inverse() * TransformFromEePose(x_model);
}

bool SimulatedController::settled() const {
  // The small slack absorbs the rounding of summed time steps (20 x 0.01 s < 0.2 s).
  return !refused_ && q_ == q_target_ && time_at_target_ + 1e-9 >= options_.settle_time;
}

bool SimulatedController::moving() const { return q_ != q_target_; }

JointVector SimulatedController::EncoderReading(std::mt19937_64& rng) const {
  std::normal_distribution<double> normal(0.0, 1.0);
  JointVector reading;
  for (int i = 0; i < 4; ++i) reading[i] = WrapAngle(q_[i] + options_.sigma_q * normal(rng));
  return reading;
}

RigidTransform SimulatedController::true_X_CT() const {
  return truth_.X_BC.inverse() * X_BE_ * truth_.X_TE.inverse();
}

bool SimulatedController::TruePoseFrom(const JointVector& q, const EePose& seed,
                                       EePose* x_model) const {
  FkOptions options;
  options.retry_from_centre = false;  // the centre may lie on another branch
  const FkResult fk = ForwardKinematics(*true_model_, q, seed, options);
  if (!fk.ok()) return false;
  *x_model = fk.x;
  return true;
}

bool SimulatedController::TruePoseFromHome(const JointVector& q, EePose* x_model) const {
  const JointVector delta = WrappedDifference(q, q_home_);
  // Steps of at most 0.01 rad: each pose a few millimetres from the last.
  const int steps = std::max(1, static_cast<int>(std::ceil(delta.cwiseAbs().maxCoeff() / 0.01)));
  EePose x = x_home_model_;
  for (int k = 1; k <= steps; ++k) {
    const JointVector q_k = q_home_ + (static_cast<double>(k) / steps) * delta;
    if (!TruePoseFrom(q_k, x, &x)) return false;
  }
  *x_model = x;
  return true;
}

}  // namespace h4::host
