// Identifiability analysis (paper III.C): the SVD of the column-scaled identification
// Jacobian over the free parameters. A singular value below a threshold (relative to the
// largest) is a direction the data cannot see; one parameter of that direction is fixed,
// chosen among those that make it up by the paper's preferences (Model 12: X_TE.tz,
// X_TE.rx, X_TE.ry, d; Model 31: also d and an angle about z_B), and the SVD is redone
// until the scaled Jacobian has full rank.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/identification/parameter_vector.h"
#include "host/kinematics/model_kind.h"

namespace h4::host {

struct IdentifiabilityOptions {
  /// A direction with singular value / largest below this is unidentifiable. The data's
  /// weakest real directions sit near 1e-3 on the paper's grid; exact invariances at 1e-9
  /// and below; second-order effects (board tilt under eq. (3)) in between.
  double relative_singular_value_threshold = 1e-5;
  /// Parameters whose share of a null direction is at least this fraction of the largest
  /// share are candidates for fixing; the first in `preferences` among them is fixed.
  double candidate_fraction = 0.3;
  /// Names in order of preference for fixing; empty: DefaultFixPreferences(model).
  std::vector<std::string> preferences;
  /// Parameters whose effect is second order at the start point (the paper's board tilt
  /// X_TE.rx, X_TE.ry under eq. (3) / (5): first order only through the residual tilt of
  /// the measured X_BE). One is fixed when its column norm is below second_order_fraction
  /// of the largest X_BC rotation column (same units, rad), before the SVD.
  std::vector<std::string> second_order_candidates;
  double second_order_fraction = 0.02;
};

/// The paper's choices: Model 12: X_TE.tz, X_TE.rx, X_TE.ry, d. Model 31: d, X_TE.tz,
/// X_TE.rx, X_TE.ry, X_TE.rz (the paper's angle about z_B), X_BC.rz.
std::vector<std::string> DefaultFixPreferences(ModelKind model);

struct FixedByAnalysis {
  std::string name;
  std::string reason;  ///< the null direction it broke, with its make-up
};

struct IdentifiabilityReport {
  Eigen::VectorXd singular_values;  ///< of the final scaled Jacobian, descending
  double condition_number = 0.0;    ///< largest / smallest singular value, after fixing
  std::vector<FixedByAnalysis> fixed;
  std::vector<std::string> log;  ///< one line per finding
};

/// Analyses J_full (residuals x p->size(), the Jacobian by all parameters) over p's free
/// parameters and fixes the unidentifiable ones in *p (at their current values). Throws
/// std::runtime_error when J_full holds inf or NaN.
IdentifiabilityReport AnalyzeIdentifiability(const Eigen::MatrixXd& J_full, ModelKind model,
                                             const IdentifiabilityOptions& options,
                                             ParameterVector* p);

/// Singular values (descending) and right singular vectors of a tall matrix, through the
/// SVD of the R factor of its QR decomposition (same values, far cheaper for 500 x 40).
void TallSvd(const Eigen::MatrixXd& J, Eigen::VectorXd* singular_values, Eigen::MatrixXd* V);

/// The triangular factor R (cols x cols) of J's QR decomposition, J^T J = R^T R; J itself
/// when J is not tall.
Eigen::MatrixXd TallR(const Eigen::MatrixXd& J);

/// Singular values (descending) of M from the eigenvalues of its Gram matrix M^T M (also
/// returned when `gram` is non-null), a fraction of the cost of a QR and a Jacobi SVD.
/// Squaring loses the singular values below ~1e-7 of the largest, so this returns false
/// (outputs unspecified) unless the smallest is at least `min_ratio` (>= 1e-6) of the
/// largest: callers then decide with the SVD, and every decision above that ratio is the
/// same as the SVD's.
bool SingularValuesIfWellConditioned(const Eigen::MatrixXd& M, double min_ratio,
                                     Eigen::VectorXd* singular_values,
                                     Eigen::MatrixXd* gram = nullptr);

/// The free columns of J_full, in p.FreeIndices() order.
Eigen::MatrixXd FreeColumns(const Eigen::MatrixXd& J_full, const ParameterVector& p);

}  // namespace h4::host
