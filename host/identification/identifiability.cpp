// Identifiability by the SVD of the scaled Jacobian; see identifiability.h.
#include "host/identification/identifiability.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <fmt/format.h>

#include "host/identification/least_squares.h"

namespace h4::host {
namespace {

// Relative column norm below which a parameter has no effect at all.
constexpr double kNoEffect = 1e-10;

}  // namespace

std::vector<std::string> DefaultFixPreferences(ModelKind model) {
  if (model == ModelKind::k31) {
    return {"d", "X_TE.tz", "X_TE.rx", "X_TE.ry", "X_TE.rz", "X_BC.rz"};
  }
  return {"X_TE.tz", "X_TE.rx", "X_TE.ry", "d"};
}

Eigen::MatrixXd TallR(const Eigen::MatrixXd& J) {
  const Eigen::Index n = J.cols();
  if (J.rows() <= n) return J;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J);
  return qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
}

void TallSvd(const Eigen::MatrixXd& J, Eigen::VectorXd* singular_values, Eigen::MatrixXd* V) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(TallR(J), Eigen::ComputeFullV);
  *singular_values = svd.singularValues();
  *V = svd.matrixV();
}

bool SingularValuesIfWellConditioned(const Eigen::MatrixXd& M, double min_ratio,
                                     Eigen::VectorXd* singular_values, Eigen::MatrixXd* gram) {
  if (M.cols() == 0 || !(min_ratio >= 1e-6)) return false;
  Eigen::MatrixXd A(M.cols(), M.cols());
  A.setZero();
  A.selfadjointView<Eigen::Lower>().rankUpdate(M.transpose());
  if (gram != nullptr) {
    A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
    *gram = A;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(A, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) return false;
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  const double largest = lambda[lambda.size() - 1];
  if (!(largest > 0) || !(lambda[0] >= min_ratio * min_ratio * largest)) return false;
  *singular_values = lambda.reverse().cwiseSqrt();
  return true;
}

Eigen::MatrixXd FreeColumns(const Eigen::MatrixXd& J_full, const ParameterVector& p) {
  const std::vector<int> free = p.FreeIndices();
  Eigen::MatrixXd J(J_full.rows(), static_cast<Eigen::Index>(free.size()));
  for (size_t k = 0; k < free.size(); ++k)
    J.col(static_cast<Eigen::Index>(k)) = J_full.col(free[k]);
  return J;
}

namespace {

// Parameters whose effect is second order at the start point, fixed before the SVD when
// their column is small against the camera rotation columns (same units, rad).
void FixSecondOrderParameters(const Eigen::MatrixXd& J_full, const IdentifiabilityOptions& options,
                              ParameterVector* p, IdentifiabilityReport* report) {
  double camera_rotation_norm = 0.0;
  for (int k = p->bc_offset() + 3; k < p->bc_offset() + 6; ++k) {
    camera_rotation_norm = std::max(camera_rotation_norm, J_full.col(k).norm());
  }
  for (const std::string& name : options.second_order_candidates) {
    const int index = p->IndexOf(name);
    if (index < 0 || !p->is_free(index)) continue;
    const double ratio = J_full.col(index).norm() / std::max(camera_rotation_norm, 1e-300);
    if (ratio < options.second_order_fraction) {
      const std::string reason = fmt::format(
          "unidentifiable: second-order effect only (column {:.1e} of the camera rotation "
          "columns)",
          ratio);
      p->Fix(index, reason);
      report->fixed.push_back({name, reason});
      report->log.push_back("fixed " + name + ": " + reason);
    }
  }
}

// The free columns scaled to unit norm. A column at rounding level (an effect that
// vanishes exactly, e.g. d in Model 12) would be blown up to a random unit column by the
// scaling: it is zeroed instead.
Eigen::MatrixXd ScaledFreeColumns(const Eigen::MatrixXd& J_full, const ParameterVector& p) {
  Eigen::MatrixXd J = FreeColumns(J_full, p);
  const Eigen::VectorXd norms = J.colwise().norm().transpose();
  for (Eigen::Index k = 0; k < J.cols(); ++k) {
    if (!(norms[k] > kNoEffect * norms.maxCoeff())) J.col(k).setZero();
  }
  return J * ColumnScale(J).cwiseInverse().asDiagonal();
}

// The right singular vectors whose singular value is below `limit`, smallest first.
Eigen::MatrixXd NullSpace(const Eigen::MatrixXd& V, const Eigen::VectorXd& singular_values,
                          double limit) {
  const Eigen::Index last = singular_values.size() - 1;
  Eigen::Index null_count = 0;
  while (null_count <= last && !(singular_values[last - null_count] >= limit)) ++null_count;
  Eigen::MatrixXd null_space(V.rows(), null_count);
  for (Eigen::Index i = 0; i < null_count; ++i) null_space.col(i) = V.col(last - i);
  return null_space;
}

// The null direction's make-up: its main components, largest first.
std::string MakeUp(const Eigen::VectorXd& v, const std::vector<int>& free,
                   const ParameterVector& p) {
  const double v_max = v.cwiseAbs().maxCoeff();
  std::vector<std::pair<double, std::string>> parts;
  for (size_t k = 0; k < free.size(); ++k) {
    const double share = std::abs(v[static_cast<Eigen::Index>(k)]);
    if (share >= 0.1 * v_max) parts.emplace_back(share, p.names()[static_cast<size_t>(free[k])]);
  }
  std::sort(parts.rbegin(), parts.rend());
  std::string makeup;
  for (const auto& [share, name] : parts) {
    makeup += (makeup.empty() ? "" : ", ") + name + fmt::format(" {:.2f}", share);
  }
  return makeup;
}

// The free parameter (its index in `free`) that breaks the null direction v: the first of
// the preferences among v's main components, else v's largest component.
Eigen::Index ChooseParameterToFix(const Eigen::VectorXd& v, const std::vector<int>& free,
                                  const std::vector<bool>& fixed_now,
                                  const std::vector<std::string>& preferences,
                                  double candidate_fraction, const ParameterVector& p) {
  const double v_max = v.cwiseAbs().maxCoeff();
  for (const std::string& name : preferences) {
    const int index = p.IndexOf(name);
    const auto it = std::find(free.begin(), free.end(), index);
    if (index < 0 || it == free.end() || fixed_now[static_cast<size_t>(it - free.begin())])
      continue;
    if (std::abs(v[it - free.begin()]) >= candidate_fraction * v_max) return it - free.begin();
  }
  Eigen::Index chosen = -1;
  v.cwiseAbs().maxCoeff(&chosen);
  return chosen;
}

// The SVD of one round, on the scaled free columns J.
struct RoundSvd {
  const Eigen::MatrixXd& J;
  double largest = 0.0;
  double smallest_ratio = 0.0;  ///< smallest / largest singular value
};

// Breaks every direction of null_space (smallest singular value first) by fixing one
// parameter each; the later ones are made free of the parameters already fixed by
// eliminating their components along the earlier ones (they stay in the near-null space,
// and a direction made of other parameters is untouched).
void BreakNullDirections(const RoundSvd& svd, Eigen::MatrixXd null_space,
                         const std::vector<std::string>& preferences,
                         const IdentifiabilityOptions& options, ParameterVector* p,
                         IdentifiabilityReport* report) {
  const std::vector<int> free = p->FreeIndices();
  const double threshold = options.relative_singular_value_threshold;
  std::vector<bool> fixed_now(free.size(), false);
  for (Eigen::Index i = 0; i < null_space.cols(); ++i) {
    const Eigen::VectorXd v = null_space.col(i).normalized();
    const double direction_ratio = svd.largest > 0 ? (svd.J * v).norm() / svd.largest : 0.0;
    if (i > 0 && !(direction_ratio < threshold)) break;
    const Eigen::Index chosen =
        ChooseParameterToFix(v, free, fixed_now, preferences, options.candidate_fraction, *p);
    if (fixed_now[static_cast<size_t>(chosen)] || !(std::abs(v[chosen]) > 0)) break;
    const int index = free[static_cast<size_t>(chosen)];
    const std::string reason =
        fmt::format(
            "unidentifiable: scaled-Jacobian direction with singular value {:.1e} of the "
            "largest, made of ",
            i == 0 ? svd.smallest_ratio : direction_ratio) +
        MakeUp(v, free, *p);
    p->Fix(index, reason);
    fixed_now[static_cast<size_t>(chosen)] = true;
    report->fixed.push_back({p->names()[static_cast<size_t>(index)], reason});
    report->log.push_back("fixed " + p->names()[static_cast<size_t>(index)] + ": " + reason);
    for (Eigen::Index j = i + 1; j < null_space.cols(); ++j) {
      null_space.col(j) -= (null_space(chosen, j) / v[chosen]) * v;
      null_space(chosen, j) = 0.0;
    }
  }
}

// One round: the SVD of the scaled free columns, and every direction below the threshold
// broken in the same round. False when the columns have full rank (the report then holds
// the singular values and condition number). The next round's SVD checks the rank and
// catches what elimination could not settle: typically two SVDs instead of one per fixed
// parameter (Model 31 fixes up to six), and the SVDs are most of the analysis' time.
bool FixNullDirections(const Eigen::MatrixXd& J_full, const std::vector<std::string>& preferences,
                       const IdentifiabilityOptions& options, ParameterVector* p,
                       IdentifiabilityReport* report) {
  const Eigen::MatrixXd J = ScaledFreeColumns(J_full, *p);
  const double threshold = options.relative_singular_value_threshold;
  // Clearly full rank (the usual check after fixing): the eigenvalues suffice.
  if (SingularValuesIfWellConditioned(J, 10.0 * threshold, &report->singular_values)) {
    report->condition_number =
        report->singular_values[0] / report->singular_values[report->singular_values.size() - 1];
    return false;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(TallR(J), Eigen::ComputeFullV);
  report->singular_values = svd.singularValues();
  const double largest = report->singular_values[0];
  const double smallest = report->singular_values[report->singular_values.size() - 1];
  report->condition_number = smallest > 0 ? largest / smallest : INFINITY;
  const double ratio = largest > 0 ? smallest / largest : 0.0;
  if (ratio >= threshold) return false;
  BreakNullDirections({J, largest, ratio},
                      NullSpace(svd.matrixV(), report->singular_values, threshold * largest),
                      preferences, options, p, report);
  return true;
}

}  // namespace

IdentifiabilityReport AnalyzeIdentifiability(const Eigen::MatrixXd& J_full, ModelKind model,
                                             const IdentifiabilityOptions& options,
                                             ParameterVector* p) {
  IdentifiabilityReport report;
  const std::vector<std::string> preferences =
      options.preferences.empty() ? DefaultFixPreferences(model) : options.preferences;
  // inf or NaN (a start point far outside any robot, or a pose the model cannot evaluate)
  // makes every singular value NaN: no direction would ever be broken and the rounds below
  // would not end. Say so instead of fixing parameters at random.
  if (!J_full.allFinite()) {
    throw std::runtime_error(
        "identifiability analysis: the Jacobian at the start point holds inf or NaN (are the "
        "robot description's values those of a real robot?)");
  }
  FixSecondOrderParameters(J_full, options, p, &report);
  // Each round fixes at least one parameter, else it stops: at most one round per free
  // parameter, whatever the Jacobian holds.
  for (int round = 0, rounds = p->free_count(); round < rounds && p->free_count() > 0; ++round) {
    const int free_before = p->free_count();
    if (!FixNullDirections(J_full, preferences, options, p, &report)) break;
    if (p->free_count() == free_before) {
      report.log.push_back("a near-null direction could not be broken by fixing a parameter");
      break;
    }
  }
  report.log.push_back(
      fmt::format("scaled Jacobian condition number {:.3g} over {} free parameters",
                  report.condition_number, p->free_count()));
  return report;
}

}  // namespace h4::host
