// The camera's error floor of a solution (`camera_error_floor`, common/formats/README.md): the
// board pose error the calibration's residuals show beyond the camera's stated covariance,
// as a standard deviation per axis added in quadrature to each pose's stated sigma, for the
// rotation and the translation apart. A rendered or real camera states the covariance of its
// corner noise alone; the corner bias of blur and response curves and an imperfect intrinsic
// calibration add an error that does not shrink with that noise
// (common/README.md#the-camera-files-uncertainty). A factor on the stated variances instead would
// overstate that error on the poses whose stated sigmas are large
// (docs/results.md#checking-for-drift-h4cal-check: the demo's rendered camera).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/identification/identification_cost.h"
#include "host/identification/parameter_vector.h"

namespace h4::host {

/// The floor f of one part (rotation or translation) from the residuals of the poses in the
/// fit: `error2[j]` the pose's squared error over its 3 axes and `sigma[j]` its stated
/// per-axis sigma (same units). f solves sum_j error2[j] / (sigma[j]^2 + f^2) = 3 n s, with s
/// = 1 - free parameters / residuals the share of the fit's degrees of freedom left to the
/// part; 0 when the stated sigmas already explain the residuals.
double ErrorFloorOf(const std::vector<double>& error2, const std::vector<double>& sigma,
                    double dof_share);

/// Both floors at the solution `p` on the poses in the fit (their stated sigmas: the
/// dataset's, else the cost's defaults); nullopt when a pose cannot be evaluated there or the
/// fit leaves no degree of freedom.
std::optional<CameraErrorFloor> CameraErrorFloorAt(const KinematicModel& model,
                                                   const ParameterVector& p,
                                                   const std::vector<DatasetRow>& in_fit,
                                                   const CostOptions& cost);

}  // namespace h4::host
