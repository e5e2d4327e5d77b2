// The camera file's uncertainty in the pose path (common/README.md#the-camera-files-uncertainty).
// Every board pose is solved with the same intrinsics c, so an error dc of the file moves every
// pose by D_j dc (D_j = dX_CT/dc at pose j, common/camera/intrinsics_uncertainty.h) at once: an
// error shared by all the poses, which the fit cannot average out and its covariance (J^T J)^-1
// does not contain. The estimate moves with it by
//   dtheta/dc = A^-1 sum_j J_j^T W_j D_j     (A = J^T J of the weighted measurement cost,
//                                            W_j its 1/sigma weights, e_j moving by -D_j dc)
// and its covariance gains the "consider" term (dtheta/dc) C_c (dtheta/dc)^T, C_c the file's
// intrinsics_covariance: the parameters' sigmas, the predicted accuracy and the accuracy map
// then carry what the camera file does not know.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "common/camera/camera_intrinsics.h"
#include "host/formats/dataset_csv.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/uncertainty.h"

namespace h4::host {

/// What the pose path needs to know of the camera: the file (with its
/// intrinsics_covariance) and the board's corners p_TQ that the poses were solved from.
struct CameraFileUncertainty {
  CameraIntrinsics camera;
  std::vector<Eigen::Vector3d> board_points;
};

struct CameraShare {
  bool added = false;
  int poses = 0;  ///< calibration poses whose D_j could be computed
};

/// Adds the consider term to u (free parameters) from the weighted measurement cost's
/// Jacobian J_full (by all parameters) on `calib`. Does nothing when the camera has no
/// intrinsics_covariance or u has no covariance.
CameraShare AddCameraFileUncertainty(const ParameterVector& p, const Eigen::MatrixXd& J_full,
                                     const IdentificationCost& cost,
                                     const std::vector<DatasetRow>& calib,
                                     const CameraFileUncertainty& camera, Uncertainty* u);

}  // namespace h4::host
