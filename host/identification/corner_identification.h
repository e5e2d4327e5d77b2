// Identification from corners (common/README.md#identification-from-corners): the pose
// path's result refined in pixel space with the camera's intrinsics as parameters
// (corner_cost.h), then every board pose measured again from its corners with the refined
// camera, so that the pose path's machinery (cross-validation, outliers, verdict, accuracy
// map) runs on poses the camera file no longer biases.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/board/board_model.h"
#include "common/camera/board_pose_fit.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/identification/corner_cost.h"
#include "host/identification/identifiability.h"
#include "host/identification/identification.h"
#include "host/identification/joint_noise.h"
#include "host/identification/least_squares.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/uncertainty.h"
#include "host/kinematics/model_kind.h"

namespace h4::host {

/// The corners of each row (in row order) with their board points: corners of pose ids that
/// are not rows are dropped, rows without corners get none. `default_sigma_px` weighs a
/// corner without its own sigma. Throws std::invalid_argument on a corner id off the board or
/// a tag id that is not that corner's (BoardModel::CornerTagProblem).
std::vector<PoseCorners> GroupCornersByRow(const std::vector<DatasetRow>& rows,
                                           const std::vector<CornerObservation>& corners,
                                           const BoardModel& board, double default_sigma_px);

/// Throws std::invalid_argument naming `corners_name` when corners are given but none has a
/// pose id of `rows` (another campaign's corners), instead of a fit that finds "0 poses".
void RequireCornersOfDataset(const std::vector<DatasetRow>& rows,
                             const std::vector<CornerObservation>& corners,
                             const std::string& corners_name);

struct CornerFitOptions {
  /// Keep every intrinsic at the file's value (`identify --camera-fixed`).
  bool camera_fixed = false;
  /// A pose needs this many corners to enter the fit (a pose from fewer is not a pose).
  int min_corners_per_pose = 12;
  /// A corner whose squared normalised residual exceeds this times the campaign's robust
  /// scale (from the median, chi-square with 2 dof) is rejected: chi-square(2)'s 1e-4 tail.
  double corner_outlier_chi2 = 18.42;
  /// Weigh the intrinsics by what the camera file states of them (its intrinsics_covariance,
  /// CornerCost::SetCameraPrior): a calibration's knowledge is not thrown away because the
  /// robot's motion measures the camera too. Off: the corners alone determine them.
  bool use_file_covariance = true;
  /// Weigh each pose's corners by the encoder noise the residuals show (generalised least
  /// squares, CornerCost::SetJointNoiseRatio): a reading's noise moves a pose's corners
  /// together, so 144 corners are not 144 independent looks at the robot. Weighed as
  /// independent, the poses count for more than they hold and an exact camera file ends less
  /// accurate than the pose path (docs/results.md#a-real-cameras-pixels-the-image-study).
  /// Off (`identify --no-weigh-encoder-noise`): corners weighed independently, the encoder
  /// noise only in the covariance (the sandwich).
  bool weigh_joint_noise = true;
  /// A camera file without a covariance is kept as it is when the corners do not show it
  /// wrong: the Wald statistic of the refined intrinsics against the file's, under the
  /// refined ones' covariance, has an upper-tail probability of at least this. Freeing
  /// intrinsics the data cannot fault only adds their uncertainty to the robot (a uniform
  /// scale of the robot is the focal length's). 0: always refine.
  double file_consistency_significance = 0.05;
  IdentifiabilityOptions identifiability;
  LmOptions lm;
};

struct CornerFitOutcome {
  CornerFitOutcome(ParameterVector start, CameraIntrinsics file_camera)
      : parameters(std::move(start)), camera(std::move(file_camera)) {}

  ParameterVector parameters;  ///< kinematics, X_BC, X_TE and the camera block
  CameraIntrinsics camera;     ///< the refined intrinsics
  bool ok = false;
  std::string message;
  /// Of the free parameters, camera block included, widened by the joint noise.
  Uncertainty uncertainty;
  JointNoise joint_noise;  ///< the encoder noise the corner residuals show
  IdentifiabilityReport identifiability;
  MinimizerReport minimizer;
  int poses = 0;
  int corners = 0;           ///< in the fit
  int rejected_corners = 0;  ///< outliers, weight 0
  /// The camera file's intrinsics_covariance entered the fit as a prior (use_file_covariance).
  bool camera_prior = false;
  /// The file's consistency with the corners (file_consistency_significance): the Wald
  /// statistic and its upper-tail probability, when tested; `camera_kept` when the file's
  /// intrinsics were kept for it.
  std::optional<double> file_wald_statistic, file_p_value;
  bool camera_kept = false;
  double rms_px_before = 0;  ///< corner residual RMS (px, per axis) at the start
  double rms_px_after = 0;
};

/// Refines `start` (a pose-path solution of `model`'s kind, with its fixed mask) and the
/// camera's intrinsics on the corners. Parameters fixed in `start` stay fixed; the camera
/// block's parameters are freed unless options.camera_fixed, then the identifiability
/// analysis fixes what the corners cannot see (preferences: the model's, then the camera's
/// highest distortion terms first).
CornerFitOutcome FitCorners(const KinematicModel& model, ModelKind kind,
                            const ParameterVector& start, const std::vector<DatasetRow>& rows,
                            const std::vector<PoseCorners>& corners, const CameraIntrinsics& camera,
                            const CornerFitOptions& options);

/// `p` without its camera block (same kinematics, placement and fixed mask).
ParameterVector WithoutCameraBlock(const ParameterVector& p, const KinematicModel& model);

/// The board pose of each row measured again from its corners through `camera` (weighted
/// Gauss-Newton on X_CT from the row's pose), with sigma_t, sigma_r from the fit's
/// covariance (the RMS of its per-axis standard deviations). Rows with fewer than
/// `min_corners` corners, or whose fit fails, are dropped (listed in *dropped).
std::vector<DatasetRow> RefitBoardPoses(const std::vector<DatasetRow>& rows,
                                        const std::vector<PoseCorners>& corners,
                                        const CameraIntrinsics& camera, int min_corners,
                                        std::vector<int64_t>* dropped = nullptr);

/// The whole corner path after a pose-path identification (`h4cal identify --corners`): the
/// corner fit from the pose path's solution on its calibration poses, every pose measured
/// again with the refined camera, then the pose path's identification (stages, outliers,
/// cross-validation, verdict) on those poses from the corner fit's solution, so that its
/// figures judge poses the camera file no longer biases. The result carries the camera.
struct CornerPathOutcome {
  CornerFitOutcome fit;
  std::vector<DatasetRow> rows;  ///< the poses measured again (sigma_t, sigma_r filled)
  std::vector<int64_t> dropped;  ///< poses without enough corners
  IdentificationOutcome outcome;
};
CornerPathOutcome IdentifyOnCorners(const AprioriModel& apriori, ModelKind kind,
                                    const IdentificationOutcome& pose_path,
                                    const std::vector<DatasetRow>& rows,
                                    const std::vector<PoseCorners>& corners,
                                    const CameraIntrinsics& camera,
                                    const IdentificationOptions& options,
                                    const CornerFitOptions& corner_options);

/// The `camera` key of a result from a corner fit (file values from `file_camera`).
ResultCamera ResultCameraOf(const CornerFitOutcome& fit, const CameraIntrinsics& file_camera);

}  // namespace h4::host
