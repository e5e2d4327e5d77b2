// Prior kinematic analysis of the rotation axis (paper III.B); see prior_analysis.h.
#include "host/identification/prior_analysis.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "common/geometry/rotation.h"
#include "common/units.h"

namespace h4::host {
namespace {

// Poses at each end of the provisional angle order that are tried as partners.
constexpr size_t kPartnersPerEnd = 4;

struct AxisEstimate {
  bool ok = false;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double spread_deg = 0.0;
  int used = 0;
  int64_t rotations_compared = 0;
};

// The poses that can be farthest (in angle) from any pose. The board turns about one
// axis, so the pose farthest from any pose is one with an extreme angle about it: a
// provisional axis (pose 0 to the pose farthest from it) orders the poses by angle, and the
// kPartnersPerEnd lowest and highest are the candidates. This keeps the analysis at
// O(n log n) (the sort) instead of comparing every pair (11 s for 8,000 rows, days for a
// million).
template <typename Relative>
std::vector<size_t> PartnerCandidates(size_t n, const Relative& relative,
                                      int64_t* rotations_compared) {
  std::vector<Eigen::Vector3d> w_from_0(n);
  size_t farthest = 0;
  for (size_t k = 0; k < n; ++k) {
    w_from_0[k] = So3Log(relative(k, 0));
    if (w_from_0[k].norm() > w_from_0[farthest].norm()) farthest = k;
  }
  *rotations_compared += static_cast<int64_t>(n);
  const Eigen::Vector3d axis = w_from_0[farthest].norm() > 0.0
                                   ? Eigen::Vector3d(w_from_0[farthest].normalized())
                                   : Eigen::Vector3d::UnitZ();
  std::vector<std::pair<double, size_t>> by_angle(n);
  for (size_t k = 0; k < n; ++k) by_angle[k] = {w_from_0[k].dot(axis), k};
  std::sort(by_angle.begin(), by_angle.end());
  std::vector<size_t> candidates;
  for (size_t i = 0; i < n; ++i) {
    if (i < kPartnersPerEnd || i + kPartnersPerEnd >= n) candidates.push_back(by_angle[i].second);
  }
  return candidates;
}

// For each pose, the rotation to the pose farthest from it in angle gives one axis
// estimate (sign-aligned with `reference`); the mean is their angle-weighted sum.
// `relative(j, k)` is the relative rotation whose axis is sought.
template <typename Relative>
AxisEstimate EstimateAxis(size_t n, const Relative& relative, const Eigen::Vector3d& reference,
                          double min_rotation) {
  AxisEstimate out;
  const std::vector<size_t> candidates = PartnerCandidates(n, relative, &out.rotations_compared);
  std::vector<Eigen::Vector3d> w_per_pose;
  for (size_t j = 0; j < n; ++j) {
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    for (size_t k : candidates) {
      const Eigen::Vector3d w = So3Log(relative(j, k));
      if (w.norm() > best.norm()) best = w;
    }
    out.rotations_compared += static_cast<int64_t>(candidates.size());
    if (best.norm() < min_rotation) continue;
    if (best.dot(reference) < 0) best = -best;
    w_per_pose.push_back(best);
  }
  if (w_per_pose.size() < 2) return out;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& w : w_per_pose) sum += w;
  out.axis = sum.normalized();
  double sum_sq = 0.0;
  for (const Eigen::Vector3d& w : w_per_pose) {
    const double angle =
        std::atan2(w.normalized().cross(out.axis).norm(), w.normalized().dot(out.axis));
    sum_sq += angle * angle;
  }
  out.spread_deg = DegreesFromRadians(std::sqrt(sum_sq / static_cast<double>(w_per_pose.size())));
  out.used = static_cast<int>(w_per_pose.size());
  out.ok = true;
  return out;
}

double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Turns the a priori camera so that its view of z_B is the measured axis, and moves it so
// that the mean board position in B stays where the a priori placed it; turns the a priori
// board so that its z_E is the measured axis in T.
void TurnPlacementOntoAxis(const std::vector<DatasetRow>& rows, const RigidTransform& X_BC_apriori,
                           const RigidTransform& X_TE_apriori, PriorAnalysis* out) {
  const Eigen::Matrix3d& R_BC0 = X_BC_apriori.rotation();
  const Eigen::Matrix3d& R_TE0 = X_TE_apriori.rotation();
  const Eigen::Vector3d b = R_BC0 * out->axis_C;
  const Eigen::Matrix3d R_fix =
      Eigen::Quaterniond::FromTwoVectors(b, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d R_BC = R_fix * R_BC0;
  Eigen::Vector3d p_CE_mean = Eigen::Vector3d::Zero();
  for (const DatasetRow& row : rows) p_CE_mean += row.X_CT * X_TE_apriori.translation();
  p_CE_mean /= static_cast<double>(rows.size());
  out->X_BC = RigidTransform(R_BC, X_BC_apriori.translation() + (R_BC0 - R_BC) * p_CE_mean);
  out->camera_axis_correction_deg = DegreesFromRadians(AngleBetween(b, Eigen::Vector3d::UnitZ()));

  const Eigen::Vector3d c = R_TE0 * Eigen::Vector3d::UnitZ();
  const Eigen::Matrix3d R_fix_T =
      Eigen::Quaterniond::FromTwoVectors(c, out->axis_T).toRotationMatrix();
  out->X_TE = RigidTransform(R_fix_T * R_TE0, X_TE_apriori.translation());
  out->board_axis_correction_deg = DegreesFromRadians(AngleBetween(c, out->axis_T));
}

}  // namespace

PriorAnalysis AnalyzeRotationAxis(const std::vector<DatasetRow>& rows,
                                  const RigidTransform& X_BC_apriori,
                                  const RigidTransform& X_TE_apriori,
                                  const PriorAnalysisOptions& options) {
  PriorAnalysis out;
  out.X_BC = X_BC_apriori;
  out.X_TE = X_TE_apriori;
  if (rows.size() < 3) {
    out.message = fmt::format("prior analysis needs at least 3 poses, got {}", rows.size());
    return out;
  }
  const Eigen::Matrix3d& R_BC0 = X_BC_apriori.rotation();
  const Eigen::Matrix3d& R_TE0 = X_TE_apriori.rotation();
  const auto R = [&](size_t j) -> const Eigen::Matrix3d& { return rows[j].X_CT.rotation(); };
  // R_CT_j R_CT_k^T = R_CB Rz(theta_j - theta_k) R_BC turns about R_CB z_B.
  const AxisEstimate in_C = EstimateAxis(
      rows.size(), [&](size_t j, size_t k) { return Eigen::Matrix3d(R(j) * R(k).transpose()); },
      R_BC0.transpose() * Eigen::Vector3d::UnitZ(), options.min_rotation);
  // R_CT_j^T R_CT_k = R_TE Rz(theta_k - theta_j) R_TE^T turns about R_TE z_E.
  const AxisEstimate in_T = EstimateAxis(
      rows.size(), [&](size_t j, size_t k) { return Eigen::Matrix3d(R(j).transpose() * R(k)); },
      R_TE0 * Eigen::Vector3d::UnitZ(), options.min_rotation);
  out.rotations_compared = in_C.rotations_compared + in_T.rotations_compared;
  if (!in_C.ok || !in_T.ok) {
    out.message = fmt::format(
        "prior analysis: the poses do not turn enough about the axis (need pairs turned by more "
        "than {:f} deg)",
        DegreesFromRadians(options.min_rotation));
    return out;
  }
  out.axis_C = in_C.axis;
  out.axis_T = in_T.axis;
  out.axis_spread_deg = in_C.spread_deg;
  out.axis_spread_T_deg = in_T.spread_deg;
  out.poses_used = in_C.used;
  for (size_t j = 0; j < rows.size(); ++j) {
    out.relative_theta.push_back(So3Log(R(j) * R(0).transpose()).dot(out.axis_C));
  }

  TurnPlacementOntoAxis(rows, X_BC_apriori, X_TE_apriori, &out);
  out.message = fmt::format(
      "rotation axis from {} poses: spread {:.3f} deg in C, {:.3f} deg in T; a priori camera "
      "axis off by {:.2f} deg, board axis by {:.2f} deg",
      out.poses_used, out.axis_spread_deg, out.axis_spread_T_deg, out.camera_axis_correction_deg,
      out.board_axis_correction_deg);
  out.ok = true;
  return out;
}

}  // namespace h4::host
