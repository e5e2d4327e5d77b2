// What the pose fit's residuals say about each corner's own error, apart from the camera
// model's misfit: the exported corners' sigma_px (common/formats/README.md#board-corners-csv)
// is the corner's noise, which a consumer that refines the camera (the host's corner path)
// must not find inflated by the misfit of the camera file h4cam used.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "firmware/detection/corner_observation.h"

namespace h4::cam {

/// Corner indices grouped by edge group (a corner outside any group is a group of its own):
/// the corners whose edge-fit noise is shared (corner_observation.h, CornerNoisePx).
std::vector<std::vector<Eigen::Index>> CornersByEdgeGroup(
    const std::vector<CornerObservation>& corners);

/// Variance per coordinate (px^2) of the pose fit's residuals `r` beyond the edge fits' noise
/// that neither the fit's parameters (the columns of `J`) nor a field smooth over the board
/// (a quadratic in u and v per axis) explain: the error of the corners themselves (the edge
/// model's bias under blur or a response curve, pixel locking), without the misfit a wrong
/// camera file leaves, which varies smoothly across the board (a focal length, distortion or
/// principal point error). Estimated as `excess` is in the pose covariance (pose_estimator.cpp,
/// EdgeNoiseCovariance): the residual sum beyond what the noise alone would leave and beyond
/// twice its spread, over the degrees of freedom left. -1 when fewer than 12 degrees of
/// freedom are left to tell (too few corners).
double ExcessBeyondSmoothField(const std::vector<CornerObservation>& corners,
                               const Eigen::MatrixXd& J, const Eigen::VectorXd& r);

}  // namespace h4::cam
