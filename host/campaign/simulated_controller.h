// The simulated H4 controller behind `h4cal sim-robot`, without any I/O: it accepts targets
// (an end-effector pose, converted to joints by the A PRIORI Model 12's inverse kinematics
// as a real controller would, or joints), moves the TRUE robot's joints toward them at a
// finite speed, reports "settled" after a dwell at the target, and gives the true board pose
// X_CT = inv(X_BC) * X_BE * inv(X_TE) (paper eq. (6)) from the true forward kinematics.
//
// The forward kinematics has several solutions for one set of joints (assembly modes); the
// one the robot is in must not depend on the path there (issue 27 point 11: continued from
// step to step along a plan, it left its branch and the board's yaw drifted by tens of
// degrees). So each target's pose is solved once, when it is accepted, from a start on the
// right branch: the commanded pose for a pose target (the true robot misses it by
// millimetres), the home pose followed along the straight joint line from home for a joint
// target. While moving, each step starts from the pose between the motion's two ends.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

struct SimulatedControllerOptions {
  double joint_speed = 0.5;  ///< rad/s, the fastest joint's speed (all joints arrive together)
  double settle_time = 0.2;  ///< s at the target before settled() becomes true
  double sigma_q = 2e-5;     ///< encoder noise per reading, rad (one sigma)
  /// Joint limits: a target whose joints differ (wrapped) from the home joints by more than
  /// this is refused, rad. The paper's 81-pose grid needs about 0.6 rad.
  double joint_range = 1.5;
  /// The encoder range (MIN, MAX) every joint must stay in, rad, as `plan` and `collect
  /// --joint-range-deg` state it (sim-robot --joint-range-deg); none: joint_range alone.
  std::optional<Eigen::Vector2d> joint_limits;
  EePose home = EePose(0.0, 0.0, -0.45, 0.0);  ///< start pose in B (the workspace centre), m, rad

  /// False (and *why says which) when an option is out of range.
  bool IsValid(std::string* why) const;
};

/// Named by ToString, in this order (simulated_controller.cpp).
enum class TargetStatus {
  kAccepted,       ///< moving to it (or already there: a repeated target changes nothing)
  kUnreachable,    ///< the a priori IK has no solution, or the true robot cannot assemble
  kOutsideLimits,  ///< beyond options.joint_range from home, or outside options.joint_limits
  kInvalid,        ///< non-finite numbers
};
/// "accepted", "unreachable", "outside joint limits", "invalid".
const char* ToString(TargetStatus status);

struct TargetResult {
  TargetStatus status = TargetStatus::kInvalid;
  std::string reason;                          ///< why it was refused (empty when accepted)
  JointVector q_target = JointVector::Zero();  ///< the joint target (accepted only)
  bool ok() const { return status == TargetStatus::kAccepted; }
};

class SimulatedController {
 public:
  /// `truth` is the true geometry (joints and X_CT come from it); `apriori` and
  /// `apriori_assembly` the Model 12 the controller believes (used for pose targets only).
  /// Starts at rest at options.home through the TRUE inverse kinematics, pose id -1, settled.
  /// Throws std::invalid_argument when the options are invalid or the true robot cannot reach
  /// the home pose.
  SimulatedController(const SimulatedRobot& truth, const Model12Parameters& apriori,
                      const Assembly& apriori_assembly,
                      const SimulatedControllerOptions& options = SimulatedControllerOptions{});
  ~SimulatedController();
  SimulatedController(const SimulatedController&) = delete;
  SimulatedController& operator=(const SimulatedController&) = delete;

  /// A target (X, Y, Z, theta) of X_BE in B, m and rad: joints from the a priori IK.
  TargetResult SetPoseTarget(int64_t pose_id, const EePose& x_B);
  /// A joint target q1..q4, rad (encoder values).
  TargetResult SetJointTarget(int64_t pose_id, const JointVector& q);

  /// A target that could not be interpreted (e.g. an unknown target type): refused as
  /// kInvalid with `reason`, like any refused target (hold, not settled, pose id taken).
  TargetResult RejectTarget(int64_t pose_id, const std::string& reason);

  /// Advances the motion by dt_s seconds (negative or non-finite: ignored).
  void Step(double dt_s);

  /// The id of the last target received, accepted or not; -1 before any.
  int64_t pose_id() const { return pose_id_; }
  /// At rest at an accepted target for at least settle_time; false after a refused target
  /// until a new target is accepted.
  bool settled() const;
  bool moving() const;
  /// The last target was refused: holding still, not settled, until a new target is accepted.
  bool refused() const { return refused_; }
  /// True joints, wrapped to (-pi, pi], rad.
  const JointVector& true_joints() const { return q_; }
  /// The joints being moved to (the current joints when holding after a refused target).
  const JointVector& target_joints() const { return q_target_; }
  /// Encoder readings: true joints + N(0, sigma_q) each, wrapped, rad.
  JointVector EncoderReading(std::mt19937_64& rng) const;
  /// True end-effector pose X_BE in B at the true joints.
  const RigidTransform& true_X_BE() const { return X_BE_; }
  /// True board pose in the camera, X_CT = inv(X_BC) * X_BE * inv(X_TE).
  RigidTransform true_X_CT() const;
  /// The true joints of the home pose.
  const JointVector& home_joints() const { return q_home_; }
  const SimulatedControllerOptions& options() const { return options_; }
  /// Motion steps whose joints the true forward kinematics could not solve (the board pose
  /// then stays at the last solved pose); 0 in any sane workspace.
  int64_t fk_failures() const { return fk_failures_; }

 private:
  /// The joint target q_in, whose true pose is sought from `seed_model` (model frame) when
  /// given, else by continuation from home.
  TargetResult SetTarget(int64_t pose_id, const JointVector& q_in,
                         const std::optional<EePose>& seed_model);
  TargetResult Accept(int64_t pose_id, const JointVector& q, const EePose& x_target_model);
  TargetResult Refuse(int64_t pose_id, TargetStatus status, const std::string& reason);
  /// True forward kinematics at q from `seed` (model frame); false when it fails.
  bool TruePoseFrom(const JointVector& q, const EePose& seed, EePose* x_model) const;
  /// The true pose at q followed from home along the straight joint line: a function of q
  /// alone (the joint range keeps every target within reach of home).
  bool TruePoseFromHome(const JointVector& q, EePose* x_model) const;
  /// Sets the current pose from x_model_.
  void SetCurrentPose(const EePose& x_model);

  SimulatedRobot truth_;
  std::unique_ptr<KinematicModel> true_model_;
  std::unique_ptr<KinematicModel> apriori_model_;
  RigidTransform X_ModelB_;  // B to the true model's base frame
  SimulatedControllerOptions options_;
  JointVector q_home_ = JointVector::Zero();
  JointVector q_ = JointVector::Zero();
  JointVector q_target_ = JointVector::Zero();
  RigidTransform X_BE_;
  EePose x_model_ = EePose::Zero();  // true pose in the model's base frame
  EePose x_home_model_ = EePose::Zero();
  // The motion under way: from x_from_model_ at q_from_ to x_target_model_ at q_target_.
  JointVector q_from_ = JointVector::Zero();
  EePose x_from_model_ = EePose::Zero();
  EePose x_target_model_ = EePose::Zero();
  int64_t pose_id_ = -1;
  bool refused_ = false;         // the last target was refused: hold, never settled
  double time_at_target_ = 0.0;  // s at rest at the target
  int64_t fk_failures_ = 0;
};

}  // namespace h4::host
