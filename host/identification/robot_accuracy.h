// The accuracy a covariance predicts for the robot itself: the end-effector positions at
// the given joint readings, by the kinematic parameters (dx = -J_f_x^-1 J_f_xi dxi; X_BC,
// X_TE and a camera block do not move the robot), after the rigid registration of the base
// frame (translation, rotation about z: a base frame is a convention;
// host/validation/accuracy_map.h and true_accuracy.h register the same way). Measured on
// the board in C instead (`predicted_position_accuracy_m`), the figure carries X_BC's
// uncertainty, which a camera file's focal length error swells along the optical axis.
#pragma once

#include <optional>
#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/uncertainty.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// RMS one-sigma registered end-effector position error over `rows` (m), from u (whose
/// free_indices index p); nullopt when a pose's forward kinematics fails or u has none.
/// `board_size_sigma` (relative): the board's size uncertainty, not observable, scales the
/// whole robot: it adds sigma^2 |x - centroid|^2 to each position's variance.
std::optional<double> PredictedRobotAccuracy(const KinematicModel& model, const ParameterVector& p,
                                             const std::vector<DatasetRow>& rows,
                                             const Uncertainty& u, double board_size_sigma = 0.0);

}  // namespace h4::host
