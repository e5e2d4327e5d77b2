// The accuracy map: the predicted one-sigma positioning error of the calibrated robot over
// its workspace, from the identified parameters' covariance.
//
// A pose x is commanded through the identified model: joints q = IK(x; xi_hat). The robot,
// whose true parameters are xi, reaches the x' at which its closure equations hold,
// f(q, x', xi) = 0 (eq. (1) for Model 12, eq. (4) for Model 31). To first order,
//   x' - x = -J_f_x^-1 J_f_xi (xi - xi_hat),
// so the reached pose has covariance A C A^T, A = J_f_x^-1 J_f_xi, with C the covariance of
// the identified kinematic parameters (the camera and board placement, X_BC and X_TE, do not
// move the robot; their correlation with the kinematics is in C's kinematic block). The map
// reports sqrt(trace) of its position block and the sigma of theta, on a grid of X, Y at
// several Z and theta around the model's workspace centre; poses out of reach (inverse
// kinematics undefined) or at a singular configuration are left out.
//
// By default the map is of the error that remains after the best rigid registration of the
// base frame (translation, rotation about Z, fitted to the positions over the whole grid):
// where exactly the identified base frame lies is a convention the identifiability analysis
// fixes (for Model 31, through the camera's X_BC.rz), and a user registers the robot to the
// work anyway (touch-up); otherwise the uncertainty of a frame orientation taken from the
// camera dominates the map (README.md#validation-and-the-report). With register_base_frame
// false, the error in the model's own base frame.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/formats/identification_result.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

struct AccuracyMapOptions {
  /// X and Y from centre - half_extent to centre + half_extent in steps of step_m; the
  /// paper's grid spans +-100 mm, the map reaches a little beyond it.
  double half_extent_m = 0.150;
  double step_m = 0.025;
  /// Z levels and theta values, relative to the workspace centre (m) and absolute (rad):
  /// the paper grid's three levels (150 mm tall) and rotations.
  std::vector<double> z_offsets_m = {-0.075, 0.0, 0.075};
  std::vector<double> theta_rad = {-0.3490658503988659, 0.0, 0.3490658503988659};
  /// Remove the best rigid registration of the base frame (above).
  bool register_base_frame = true;

  bool IsValid(std::string* why) const;
};

struct AccuracyMapPoint {
  EePose x = EePose::Zero();      ///< commanded pose in the model's base frame
  double position_sigma_m = 0.0;  ///< sqrt(trace) of the position covariance
  double theta_sigma_rad = 0.0;   ///< one sigma of theta
};

struct AccuracyMap {
  ModelKind model = ModelKind::k12;
  EePose centre = EePose::Zero();  ///< the grid's centre (the model's workspace centre)
  AccuracyMapOptions options;
  std::vector<AccuracyMapPoint> points;  ///< reachable poses, Z level, theta, Y, X order
  int left_out = 0;  ///< grid poses out of reach, singular, or without a finite sigma
  /// Median and largest position sigma over the points, m (0 when none).
  double MedianPositionSigma() const;
  double MaxPositionSigma() const;
};

/// The map of `model` (the identified parameters) with C, the covariance of its kinematic
/// parameters (model.parameters() order, SI). Throws std::invalid_argument on invalid
/// options or a C of the wrong size.
AccuracyMap ComputeAccuracyMap(const KinematicModel& model, const Eigen::MatrixXd& C,
                               const AccuracyMapOptions& options = AccuracyMapOptions{});

/// What of per-pose errors (X, Y, Z, theta rows; a column per error, or per parameter for
/// a sensitivity) no rigid motion of the base frame explains: the motion (translation, a
/// rotation about Z through `centre`) fitted by least squares to the position rows over
/// every pose is taken out of every row. The same for a sensitivity (the map) and for actual
/// errors (the coverage study), so that both are judged alike.
std::vector<Eigen::MatrixXd> WithoutRigidRegistration(const std::vector<EePose>& poses,
                                                      const EePose& centre,
                                                      const std::vector<Eigen::MatrixXd>& errors);

/// What of the difference between reached and commanded poses no rigid motion of the base
/// frame explains, for motions of any size: the rotation about Z and the translation that
/// best map the commanded positions onto the reached ones (least squares, closed form) are
/// taken out; per pose (X, Y, Z, theta) of reached - moved(commanded). For small motions it
/// is WithoutRigidRegistration of the differences; a frame turned by degrees (the gauge the
/// identifiability analysis fixes at a value off the truth's) needs the exact rotation.
std::vector<Eigen::Vector4d> ResidualAfterRigidRegistration(const std::vector<EePose>& commanded,
                                                            const std::vector<EePose>& reached);

/// The map of a result: its model rebuilt with `assembly`, C from its
/// `parameter_covariance`. Empty when the result has no covariance (an older result, or
/// one whose covariance could not be computed).
std::optional<AccuracyMap> AccuracyMapOfResult(
    const IdentificationResult& result, const Assembly& assembly,
    const AccuracyMapOptions& options = AccuracyMapOptions{});

/// The map as CSV
/// (common/formats/README.md#accuracy-map-csv---report-dir-of-h4cal-identify--validate): a header,
/// then X,Y,Z,theta,position_sigma,theta_sigma per point, m and rad, in the model's base frame.
std::string AccuracyMapCsv(const AccuracyMap& map);

}  // namespace h4::host
