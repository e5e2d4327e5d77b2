// The control law of the square-path validation (paper IV.D): each planned end-effector
// pose, given in B, sent to the robot as the joints of a model's inverse kinematics, the
// model being whichever the identification found accurate (Model 12 or Model 31).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

/// Joints for a pose x_B in B, or nullopt with *why set (out of reach).
using ControlLawFunction =
    std::function<std::optional<JointVector>(const EePose& x_B, std::string* why)>;

/// The inverse kinematics of `model` as a control law. A Model 31 takes poses in its own
/// base frame B31 (origin at P_1, common/README.md#model-31-calibration-model-31-parameters):
/// X_B31B maps the planned pose there (NominalX_B31B of the a priori Model 12, model31.h); a Model
/// 12 needs none. Throws std::invalid_argument for a Model 31 without X_B31B.
ControlLawFunction InverseKinematicsControlLaw(std::shared_ptr<const KinematicModel> model,
                                               const std::optional<RigidTransform>& X_B31B);

}  // namespace h4::host
