// The candidate set of pose planning: end-effector poses (X, Y, Z, theta) in B on a
// regular grid that the robot reaches (closed-form inverse kinematics of the a priori
// Model 12 defined, joints inside a range when one is given) and at which the camera sees
// the whole board: all its corners, projected with the camera model through the a priori
// placement X_CT = inv(X_BC) X_BE inv(X_TE) (common/README.md), fall inside the image with a
// margin, the board is not tilted past a limit from the line of sight, and its centre lies
// in the camera's depth (focus) range, and the pose keeps clear of the singularity where the
// nacelle angle theta stops being held by the joints (see max_theta_gain).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/text/enum_names.h"
#include "common/units.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

struct CandidateOptions {
  /// Centre of the candidate grid in B, m (theta ignored): the paper's workspace centre.
  Eigen::Vector3d centre = Eigen::Vector3d(0.0, 0.0, -0.45);
  /// Half extent of the grid along x, y, z of B, m.
  /// (A box wider than the paper's grid: the poses that carry the most information lie at
  /// its edges; README.md#planning-the-poses-how-many-and-which.)
  Eigen::Vector3d half_extent = Eigen::Vector3d(0.25, 0.25, 0.15);
  /// Grid step along x, y, z, m.
  double position_step = 0.05;
  /// Nacelle angles, rad (default -60..60 deg by 10 deg; max_theta_gain keeps those near
  /// the theta singularity out).
  std::vector<double> theta = {RadiansFromDegrees(-60.0),
                               RadiansFromDegrees(-50.0),
                               RadiansFromDegrees(-40.0),
                               RadiansFromDegrees(-30.0),
                               RadiansFromDegrees(-20.0),
                               RadiansFromDegrees(-10.0),
                               0.0,
                               RadiansFromDegrees(10.0),
                               RadiansFromDegrees(20.0),
                               RadiansFromDegrees(30.0),
                               RadiansFromDegrees(40.0),
                               RadiansFromDegrees(50.0),
                               RadiansFromDegrees(60.0)};
  /// Joint range (encoder values, rad) every joint must stay in; unset: any angle.
  std::optional<Eigen::Vector2d> joint_range;
  /// Every outer board corner at least this far inside the image border, px.
  double image_margin_px = 20.0;
  /// Largest angle between the board normal and the line of sight to its centre, rad.
  double max_tilt = RadiansFromDegrees(60.0);
  /// Largest |d theta / dq| (rad of nacelle angle per rad of joint, the norm of theta's row
  /// of J_x_q, forward_kinematics.h) of the a priori Model 12. The gain grows without bound
  /// towards the singularity where J_f_x loses rank in theta (the nacelle turns freely);
  /// there the true robot, whose singular locus is displaced from the a priori's, may have
  /// no forward kinematics at its measured joints, and the measurement-space identification
  /// cannot be evaluated. The limit keeps the paper's grid and every pose of the earlier
  /// default grid (theta +-30 deg) as candidates (README.md#planning-the-poses-how-many-and-which).
  double max_theta_gain = 12.0;
  /// Depth range (z in C of the board centre) the camera is in focus over, m.
  double min_depth = 0.15;
  double max_depth = 2.0;

  bool IsValid(std::string* why) const;
};

/// Why a pose is not a candidate (kOk when it is).
enum class CandidateVerdict {
  kOk,
  kUnreachable,
  kJointRange,
  kOutOfImage,
  kTilt,
  kDepth,
  kNearSingular
};
inline constexpr EnumNames<CandidateVerdict, CandidateVerdict::kNearSingular>
    kCandidateVerdictNames = {"ok",
                              "unreachable",
                              "joint range",
                              "board not whole in the image",
                              "board tilted",
                              "out of the depth range",
                              "near a singularity"};
const char* ToString(CandidateVerdict verdict);

struct CandidatePose {
  EePose x_B = EePose::Zero();          ///< X_BE in B, m and rad
  JointVector q = JointVector::Zero();  ///< a priori Model 12 inverse kinematics, rad
};

/// The four outer corners p_TQ of the board (the bounding rectangle of its corners, z = 0), m.
std::vector<Eigen::Vector3d> OuterBoardCorners(const BoardModel& board);

/// |d theta / dq| at a consistent (q, x) of `model`: the norm of theta's row of J_x_q;
/// +infinity where J_f_x is singular.
double ThetaJointGain(const KinematicModel& model, const JointVector& q, const EePose& x);

/// Decides one pose. `joints` receives the a priori joints when reachable.
class CandidateFilter {
 public:
  CandidateFilter(const RobotDescription& robot, const CameraModel& camera, const BoardModel& board,
                  const CandidateOptions& options);
  CandidateVerdict Check(const EePose& x_B, JointVector* joints) const;

 private:
  CandidateVerdict CheckView(const EePose& x_B) const;

  RobotDescription robot_;
  CameraModel camera_;
  std::vector<Eigen::Vector3d> corners_T_;  // every corner of the board, p_TQ
  Eigen::Vector3d p_TBoardCentre_;
  CandidateOptions options_;
};

struct CandidateSet {
  std::vector<CandidatePose> poses;  ///< in grid order: z, y, x, theta slowest to fastest
  int examined = 0;
  /// How many grid poses each verdict rejected, indexed by CandidateVerdict.
  std::vector<int> rejected = std::vector<int>(kCandidateVerdictNames.kCount, 0);
  std::string Summary() const;
};

/// Every grid pose of `options` that CandidateFilter accepts. Throws std::invalid_argument
/// when the options are not valid.
CandidateSet MakeCandidateSet(const RobotDescription& robot, const CameraModel& camera,
                              const BoardModel& board, const CandidateOptions& options);

}  // namespace h4::host
