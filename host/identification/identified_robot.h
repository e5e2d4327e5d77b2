// An identified robot as the later programs use it (fk, ik, validate, check): a
// KinematicModel with X_BC and X_TE rebuilt from an IdentificationResult, the covariance of
// its parameters, and the figures computed from a model and a dataset: joint residuals (IK
// of the measured pose minus the reading, wrapped) and board-pose prediction errors (FK of
// the readings through the chain).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry/rigid_transform.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/identification/parameter_vector.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

struct IdentifiedRobot {
  std::unique_ptr<KinematicModel> model;
  RigidTransform X_BC;  ///< camera in the model's base frame
  RigidTransform X_TE;
};

/// Rebuilds the model of result.model (Model 12 or 31) from the result's parameters
/// (every kinematic parameter must be present) with `assembly`. Throws
/// std::invalid_argument naming the missing parameter or unknown model.
IdentifiedRobot RebuildFromResult(const IdentificationResult& result,
                                  const Assembly& assembly = Assembly{});

/// The identified camera pose in B, the frame plans and the control law command poses in
/// (host/campaign/control_law.h): a Model 12 result's X_BC as it is; a Model 31 result's
/// X_B31C moved to B with the a priori Model 12's nominal X_B31B, the transform the control
/// law maps B to B31 with (X_BC = inv(X_B31B) X_B31C). This is the model's own base frame
/// as a user of that controller sees it.
RigidTransform CameraInPlanFrame(const IdentificationResult& result,
                                 const Model12Parameters& apriori);

/// The one check that a result is Model 12's (the --from start of Model 31): throws
/// std::invalid_argument "SOURCE: USE needs a Model 12 result, this is Model 31" (without "SOURCE:
/// " when source is empty).
void RequireModel12Result(const IdentificationResult& result, const std::string& source,
                          const std::string& use);

/// The covariance of a result's parameters in the order of p (matched by name): the
/// result's `parameter_covariance`, or, for a result without it, the diagonal of its
/// sigmas (*with_correlations set false). Zero for a parameter the result does not give.
Eigen::MatrixXd ResultCovarianceFor(const IdentificationResult& result, const ParameterVector& p,
                                    bool* with_correlations = nullptr);

/// The board pose X_CT predicted from joint readings: FK (started from the model's
/// workspace centre or `guess`) through X_CT = inv(X_BC) X_BE inv(X_TE); empty when FK fails.
std::optional<RigidTransform> PredictBoardPose(const KinematicModel& model,
                                               const RigidTransform& X_BC,
                                               const RigidTransform& X_TE, const JointVector& q,
                                               const std::optional<EePose>& guess = std::nullopt);

/// Per-joint RMS (rad) of wrap(IK(X_BC X_CT X_TE) - q~) over the rows; rows out of reach
/// are skipped and counted in *unreachable.
std::array<double, 4> JointResidualRms(const KinematicModel& model, const RigidTransform& X_BC,
                                       const RigidTransform& X_TE,
                                       const std::vector<DatasetRow>& rows, int* unreachable);

/// RMS position (m) and rotation (rad) error of PredictBoardPose(q~) against the measured
/// X_CT over the rows; rows where FK fails are counted in `failed`.
struct BoardPoseErrors {
  double position_rms = 0.0;
  double rotation_rms = 0.0;
  int poses = 0;
  int failed = 0;
};
BoardPoseErrors BoardPoseErrorsOf(const KinematicModel& model, const RigidTransform& X_BC,
                                  const RigidTransform& X_TE, const std::vector<DatasetRow>& rows);

}  // namespace h4::host
