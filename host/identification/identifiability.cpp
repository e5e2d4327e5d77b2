// Identifiability by the SVD of the scaled Jacobian; see identifiability.h.
#include "host/identification/identifiability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "host/identification/least_squares.h"

namespace h4::host {
namespace {

// Relative column norm below which a parameter has no effect at all.
constexpr double kNoEffect = 1e-10;

std::string Format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

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

IdentifiabilityReport AnalyzeIdentifiability(const Eigen::MatrixXd& J_full, ModelKind model,
                                             const IdentifiabilityOptions& options,
                                             ParameterVector* p) {
  IdentifiabilityReport report;
  const std::vector<std::string> preferences =
      options.preferences.empty() ? DefaultFixPreferences(model) : options.preferences;
  // Second-order parameters against the camera rotation columns.
  double camera_rotation_norm = 0.0;
  for (int k = p->bc_offset() + 3; k < p->bc_offset() + 6; ++k) {
    camera_rotation_norm = std::max(camera_rotation_norm, J_full.col(k).norm());
  }
  for (const std::string& name : options.second_order_candidates) {
    const int index = p->IndexOf(name);
    if (index < 0 || !p->is_free(index)) continue;
    const double ratio = J_full.col(index).norm() / std::max(camera_rotation_norm, 1e-300);
    if (ratio < options.second_order_fraction) {
      const std::string reason = "unidentifiable: second-order effect only (column " +
                                 Format("%.1e", ratio) + " of the camera rotation columns)";
      p->Fix(index, reason);
      report.fixed.push_back({name, reason});
      report.log.push_back("fixed " + name + ": " + reason);
    }
  }
  // Each round: one SVD of the scaled free columns; every direction below the threshold is
  // broken in the same round (smallest first), the later ones made free of the parameters
  // already fixed by eliminating their components along the earlier ones (they stay in the
  // near-null space, and a direction made of other parameters is untouched). The next round's
  // SVD checks the rank and catches what elimination could not settle. Typically two SVDs
  // instead of one per fixed parameter (Model 31 fixes up to six): the SVDs are most of the
  // analysis' time.
  while (p->free_count() > 0) {
    const std::vector<int> free = p->FreeIndices();
    Eigen::MatrixXd J = FreeColumns(J_full, *p);
    // A column at rounding level (an effect that vanishes exactly, e.g. d in Model 12)
    // would be blown up to a random unit column by the scaling: zero it instead.
    const Eigen::VectorXd norms = J.colwise().norm().transpose();
    for (Eigen::Index k = 0; k < J.cols(); ++k) {
      if (!(norms[k] > kNoEffect * norms.maxCoeff())) J.col(k).setZero();
    }
    J = J * ColumnScale(J).cwiseInverse().asDiagonal();
    // Clearly full rank (the usual check after fixing): the eigenvalues suffice.
    if (SingularValuesIfWellConditioned(J, 10.0 * options.relative_singular_value_threshold,
                                        &report.singular_values)) {
      report.condition_number =
          report.singular_values[0] / report.singular_values[report.singular_values.size() - 1];
      break;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(TallR(J), Eigen::ComputeFullV);
    report.singular_values = svd.singularValues();
    const Eigen::MatrixXd& V = svd.matrixV();
    const Eigen::Index last = report.singular_values.size() - 1;
    const double largest = report.singular_values[0];
    const double smallest = report.singular_values[last];
    report.condition_number = smallest > 0 ? largest / smallest : INFINITY;
    const double ratio = largest > 0 ? smallest / largest : 0.0;
    if (ratio >= options.relative_singular_value_threshold) break;

    Eigen::Index null_count = 0;
    while (null_count <= last && !(report.singular_values[last - null_count] >=
                                   options.relative_singular_value_threshold * largest)) {
      ++null_count;
    }
    Eigen::MatrixXd null_space(V.rows(), null_count);  // smallest singular value first
    for (Eigen::Index i = 0; i < null_count; ++i) null_space.col(i) = V.col(last - i);
    std::vector<bool> fixed_now(free.size(), false);
    for (Eigen::Index i = 0; i < null_count; ++i) {
      const Eigen::VectorXd v = null_space.col(i).normalized();
      const double direction_ratio = largest > 0 ? (J * v).norm() / largest : 0.0;
      if (i > 0 && !(direction_ratio < options.relative_singular_value_threshold)) break;
      // The null direction's make-up; fix the preferred parameter among its main components.
      const double v_max = v.cwiseAbs().maxCoeff();
      Eigen::Index chosen = -1;
      for (const std::string& name : preferences) {
        const int index = p->IndexOf(name);
        const auto it = std::find(free.begin(), free.end(), index);
        if (index < 0 || it == free.end() || fixed_now[static_cast<size_t>(it - free.begin())])
          continue;
        if (std::abs(v[it - free.begin()]) >= options.candidate_fraction * v_max) {
          chosen = it - free.begin();
          break;
        }
      }
      if (chosen < 0) v.cwiseAbs().maxCoeff(&chosen);
      if (fixed_now[static_cast<size_t>(chosen)] || !(std::abs(v[chosen]) > 0)) break;

      std::vector<std::pair<double, std::string>> parts;
      for (size_t k = 0; k < free.size(); ++k) {
        const double share = std::abs(v[static_cast<Eigen::Index>(k)]);
        if (share >= 0.1 * v_max)
          parts.emplace_back(share, p->names()[static_cast<size_t>(free[k])]);
      }
      std::sort(parts.rbegin(), parts.rend());
      std::string makeup;
      for (const auto& [share, name] : parts) {
        makeup += (makeup.empty() ? "" : ", ") + name + Format(" %.2f", share);
      }
      const int index = free[static_cast<size_t>(chosen)];
      const std::string reason = "unidentifiable: scaled-Jacobian direction with singular value " +
                                 Format("%.1e", i == 0 ? ratio : direction_ratio) +
                                 " of the largest, made of " + makeup;
      p->Fix(index, reason);
      fixed_now[static_cast<size_t>(chosen)] = true;
      report.fixed.push_back({p->names()[static_cast<size_t>(index)], reason});
      report.log.push_back("fixed " + p->names()[static_cast<size_t>(index)] + ": " + reason);
      // The remaining directions without the fixed parameter: still (near) null for the
      // columns left free.
      for (Eigen::Index j = i + 1; j < null_count; ++j) {
        null_space.col(j) -= (null_space(chosen, j) / v[chosen]) * v;
        null_space(chosen, j) = 0.0;
      }
    }
  }
  report.log.push_back("scaled Jacobian condition number " +
                       Format("%.3g", report.condition_number) + " over " +
                       std::to_string(p->free_count()) + " free parameters");
  return report;
}

}  // namespace h4::host
