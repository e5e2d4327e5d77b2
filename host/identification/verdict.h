// The verdict on an identification: whether the identified robot is accurate, and if not
// which case it is, in words a technician acts on. It is decided from a chi-square test of
// the residuals normalised by the pose covariance (what the camera's noise model predicts
// against what the fit left), the identifiability analysis (covariance, condition number),
// the pose counts and the share of poses out of reach or rejected, and how far the fit had
// to move the kinematic parameters from the a priori robot (common/README.md names).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host/formats/identification_result.h"
#include "host/kinematics/model_kind.h"

namespace h4::host {

/// Coded by VerdictCode, in this order (verdict.cpp).
enum class Verdict {
  kGood,                     ///< accurate: the misfit is what the camera noise predicts
  kModelCannotDescribe,      ///< consistent data the model cannot fit (Model 12 on a 31 robot)
  kInconsistentWithApriori,  ///< units, frames, joint order or offsets of robot.yaml wrong
  kNotIdentifiable,          ///< no covariance, or parameters the poses cannot separate
  kTooFewPoses,              ///< not enough poses for the parameters and a test of the fit
  /// the corner path's corners carry a sigma far above their scatter: the chi-square test
  /// cannot judge the fit (corner_checks.h FlagOverstatedCornerNoise)
  kNoiseOverstated,
};

/// The advice of a Model 31 fit that cannot describe the robot from board poses alone: the
/// robot and the mounts. The corner path replaces it with what the corner residuals' pattern
/// over the image shows (host/validation/corner_residual_map.h CornerResidualPatternAdvice).
inline constexpr const char* kModel31MisfitAdvice =
    "Check that the robot is rigid and settled at every pose (backlash, flexure, loose camera "
    "or board) and that the camera's pose covariance is right.";

/// "good", "model_cannot_describe", "inconsistent_with_apriori", "not_identifiable",
/// "too_few_poses", "noise_overstated": the `verdict.code` of the result JSON.
const char* VerdictCode(Verdict verdict);

struct VerdictOptions {
  /// Least poses in the fit, and least residuals per free parameter: below either the fit
  /// can follow the noise and the chi-square test has too few degrees of freedom to judge it.
  /// Three residuals per parameter leave two thirds of them to the test, and admit what a
  /// planned design needs: `h4cal plan`'s 25 poses (150 residuals for Model 31's 40
  /// parameters) match the paper's 71-pose grid (docs/results.md#planned-poses-against-the-grid).
  int min_poses = 20;
  double min_residuals_per_parameter = 3.0;
  /// The chi-square test: the fit is consistent with the noise model when the upper-tail
  /// probability of its chi-square is at least `significance`, or its reduced chi-square is
  /// at most `tolerated_reduced_chi2`. The tolerance is there because a camera's pose
  /// covariance is itself an estimate: the README's vision table has sigma / actual error
  /// between 0.7 and 1.73, i.e. chi-square / dof up to 3 on data the model fits.
  double significance = 1e-3;
  double tolerated_reduced_chi2 = 3.0;
  /// Below this board position misfit left unexplained by the noise model (misfit x
  /// sqrt(1 - 1 / chi2_dof)) a fit the test rejects is still accurate: a quarter of the
  /// tightest accuracy the method targets (README: 0.10 mm for Model 12, 0.20 mm for
  /// Model 31); the test then only says the camera's pose covariance is optimistic (the
  /// sigmas are scaled by the reduced chi-square). The live demo's rendered camera fits
  /// Model 31 to 0.015 mm with chi-square / dof 3.1. m.
  double negligible_misfit_m = 0.025e-3;
  /// A board position misfit (RMS over the poses in the fit) at or above this is not a
  /// model's structural error (millimetres of assembly error) but data the a priori robot
  /// cannot be made to match: units, frames, joint order, offsets. m.
  double inconsistent_misfit_m = 10e-3;
  /// More than this share of the poses out of reach of the a priori or identified robot
  /// (or rejected as outliers) means the data do not belong to this robot.
  double max_out_of_reach_fraction = 0.1;
  double max_rejected_fraction = 0.15;
  /// A kinematic length moved by more than this fraction of its a priori value, or an
  /// angle by more than this, is not an assembly error (rad).
  double max_relative_length_change = 0.25;
  double max_angle_change = 0.35;  // 20 deg
  /// Above this condition number of the scaled Jacobian the poses cannot separate the
  /// parameters well enough for their sigmas to mean anything.
  double max_condition_number = 1e5;

  bool IsValid(std::string* why) const;
};

/// The fewest poses a fit of `free_parameters` needs not to be judged too_few_poses, with
/// `residuals_per_pose` residuals each (6: a board pose): options.min_poses, or three
/// residuals per free parameter when that is more.
int MinimumPosesInFit(int free_parameters, double residuals_per_pose = 6.0,
                      const VerdictOptions& options = VerdictOptions{});

/// Everything the verdict is decided from.
struct VerdictInputs {
  ModelKind model = ModelKind::k12;
  int poses_given = 0;      ///< rows of the dataset (calibration and held out)
  int poses_in_fit = 0;     ///< calibration poses left after outlier rejection
  int poses_rejected = 0;   ///< rejected as outliers
  int out_of_reach = 0;     ///< calibration poses the a priori or identified robot cannot reach
  int free_parameters = 0;  ///< in the final fit
  int residuals = 0;        ///< rows of the final cost
  bool converged = false;   ///< the final stage converged
  bool has_covariance = false;
  double chi2 = 0.0;  ///< sum of squared normalised residuals at the solution
  double condition_number = 0.0;
  double position_misfit_m = 0.0;  ///< RMS board position residual over the poses in the fit
  /// The largest departure from the a priori: relative for lengths, rad for angles.
  double largest_length_change = 0.0;
  double largest_angle_change = 0.0;
  std::string largest_length_parameter, largest_angle_parameter;
  bool dataset_sigmas = true;  ///< false: the dataset has no pose covariance (defaults used)
};

/// The upper-tail probability P(X >= chi2) of a chi-square with `dof` degrees of freedom
/// (Wilson-Hilferty cube-root normal approximation, relative error under 1e-2 for dof >= 10).
double ChiSquareUpperTail(double chi2, double dof);

/// The verdict, its text and the figures that decided it.
ResultVerdict DecideVerdict(const VerdictInputs& inputs, const VerdictOptions& options,
                            Verdict* verdict = nullptr);

/// The code parsed back ("good" ...); nullopt when unknown.
std::optional<Verdict> ParseVerdictCode(const std::string& code);

}  // namespace h4::host
