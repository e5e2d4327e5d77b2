// Identifiability by the SVD of the scaled Jacobian; see identifiability.h.
#include "host/identification/identifiability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

std::vector<std::string> DefaultFixPreferences(const std::string& model_name) {
  if (model_name == "31") {
    return {"d", "X_TE.tz", "X_TE.rx", "X_TE.ry", "X_TE.rz", "X_BC.rz"};
  }
  return {"X_TE.tz", "X_TE.rx", "X_TE.ry", "d"};
}

void TallSvd(const Eigen::MatrixXd& J, Eigen::VectorXd* singular_values, Eigen::MatrixXd* V) {
  const Eigen::Index n = J.cols();
  Eigen::MatrixXd R;
  if (J.rows() > n) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J);
    R = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
  } else {
    R = J;
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullV);
  *singular_values = svd.singularValues();
  *V = svd.matrixV();
}

Eigen::MatrixXd FreeColumns(const Eigen::MatrixXd& J_full, const ParameterVector& p) {
  const std::vector<int> free = p.FreeIndices();
  Eigen::MatrixXd J(J_full.rows(), static_cast<Eigen::Index>(free.size()));
  for (size_t k = 0; k < free.size(); ++k)
    J.col(static_cast<Eigen::Index>(k)) = J_full.col(free[k]);
  return J;
}

IdentifiabilityReport AnalyzeIdentifiability(const Eigen::MatrixXd& J_full,
                                             const std::string& model_name,
                                             const IdentifiabilityOptions& options,
                                             ParameterVector* p) {
  IdentifiabilityReport report;
  const std::vector<std::string> preferences =
      options.preferences.empty() ? DefaultFixPreferences(model_name) : options.preferences;
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
    Eigen::MatrixXd V;
    TallSvd(J, &report.singular_values, &V);
    const Eigen::Index last = report.singular_values.size() - 1;
    const double largest = report.singular_values[0];
    const double smallest = report.singular_values[last];
    report.condition_number = smallest > 0 ? largest / smallest : INFINITY;
    const double ratio = largest > 0 ? smallest / largest : 0.0;
    if (ratio >= options.relative_singular_value_threshold) break;

    // The null direction's make-up; fix the preferred parameter among its main components.
    const Eigen::VectorXd v = V.col(last);
    const double v_max = v.cwiseAbs().maxCoeff();
    int chosen = -1;
    for (const std::string& name : preferences) {
      const int index = p->IndexOf(name);
      const auto it = std::find(free.begin(), free.end(), index);
      if (index < 0 || it == free.end()) continue;
      if (std::abs(v[it - free.begin()]) >= options.candidate_fraction * v_max) {
        chosen = index;
        break;
      }
    }
    Eigen::Index k_max = 0;
    v.cwiseAbs().maxCoeff(&k_max);
    if (chosen < 0) chosen = free[static_cast<size_t>(k_max)];

    std::vector<std::pair<double, std::string>> parts;
    for (size_t k = 0; k < free.size(); ++k) {
      const double share = std::abs(v[static_cast<Eigen::Index>(k)]);
      if (share >= 0.1 * v_max) parts.emplace_back(share, p->names()[static_cast<size_t>(free[k])]);
    }
    std::sort(parts.rbegin(), parts.rend());
    std::string makeup;
    for (const auto& [share, name] : parts) {
      makeup += (makeup.empty() ? "" : ", ") + name + Format(" %.2f", share);
    }
    const std::string reason = "unidentifiable: scaled-Jacobian direction with singular value " +
                               Format("%.1e", ratio) + " of the largest, made of " + makeup;
    p->Fix(chosen, reason);
    report.fixed.push_back({p->names()[static_cast<size_t>(chosen)], reason});
    report.log.push_back("fixed " + p->names()[static_cast<size_t>(chosen)] + ": " + reason);
  }
  report.log.push_back("scaled Jacobian condition number " +
                       Format("%.3g", report.condition_number) + " over " +
                       std::to_string(p->free_count()) + " free parameters");
  return report;
}

}  // namespace h4::host
