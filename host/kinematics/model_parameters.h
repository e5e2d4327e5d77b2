// Each model's parameters in one table: name (common/README.md#model-12-design-model-12-parameters
// and #model-31-calibration-model-31-parameters), kind and unit, in the order of the model's
// parameter vector. The models take their names from here, and the result's reader, the
// verdict and the report tell lengths from angles by looking a name up here.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace h4 {

enum class ParameterKind {
  kPositiveLength,  ///< m, > 0: an arm, forearm, the nacelle half-length h, the base radius R
  kLength,          ///< m, any sign: a base joint position, the nacelle offset d
  kAngle,           ///< rad: a joint axis direction or an encoder offset
};

/// "m" or "rad".
std::string_view UnitOf(ParameterKind kind);

struct ModelParameter {
  std::string_view name;
  ParameterKind kind;
};

/// Model 12 (design model): h, arm, forearm, R, d, alpha1..4, q01..4.
std::span<const ModelParameter> Model12ParameterTable();

/// Model 31 (calibration model): x2..z4, psi1..4, beta1..4, q01..4, arm1..4, forearm1..4, h, d.
std::span<const ModelParameter> Model31ParameterTable();

/// The names of a table's parameters, in its order (a model's parameter_names()).
std::vector<std::string> ParameterNamesOf(std::span<const ModelParameter> table);

/// The kind of a parameter of either model, or of a family of them named without its index
/// ("alpha", "q0", "arm": robot.yaml's keys); nullopt for any other name.
std::optional<ParameterKind> ModelParameterKind(std::string_view name);

/// An arm, forearm, nacelle (h) or base radius (R) length: positive, like its robot.yaml key.
bool IsPositiveLengthParameter(std::string_view name);

/// An angle of the models, in radians: alpha_i, q0_i, psi_i, beta_i.
bool IsModelAngleParameter(std::string_view name);

/// Any angle of a result: a model angle, or a rotation rx, ry, rz of X_BC or X_TE.
bool IsAngleParameter(std::string_view name);

}  // namespace h4
