// What the name of a Model 12 / Model 31 parameter says of its quantity (common/README.md
// names them): the identification result's reader, the verdict and the report each need
// to tell lengths from angles, and read the one list here.
#pragma once

#include <string_view>

namespace h4 {

/// An arm, forearm, nacelle (h) or base radius (R) length: positive, like its robot.yaml key.
bool IsPositiveLengthParameter(std::string_view name);

/// An angle of the models, in radians: alpha_i, q0_i, psi_i, beta_i.
bool IsModelAngleParameter(std::string_view name);

/// Any angle of a result: a model angle, or a rotation rx, ry, rz of X_BC or X_TE.
bool IsAngleParameter(std::string_view name);

}  // namespace h4
