// Whether a matrix read from a file or a message is a covariance: every reader of one
// (the board pose of a campaign, the identification result's camera block) asks the same.
#pragma once

#include <string>

#include <Eigen/Core>

namespace h4 {

/// Empty when C is a covariance: square, finite, symmetric (each pair to 1e-9 of
/// sqrt(C_ii C_jj)) and positive semi-definite (its smallest eigenvalue at least -1e-9
/// times its largest); else why ("not positive semi-definite: an eigenvalue is -0.5").
/// A diagonal check alone passes [[1, 2], [2, 1]], whose eigenvalues are 3 and -1.
std::string CovarianceProblem(const Eigen::MatrixXd& C);

}  // namespace h4
