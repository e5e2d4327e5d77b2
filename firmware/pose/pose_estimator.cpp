// Planar PnP with distortion; see pose_estimator.h.
#include "firmware/pose/pose_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <fmt/format.h>

#include "common/geometry/rotation.h"
#include "firmware/detection/planar_pose_starts.h"
#include "firmware/pose/corner_noise.h"

namespace h4::cam {
namespace {

// The fitted parameters: the pose and the erosion coefficients (px) of the basis
// ErosionBasis describes.
struct State {
  RigidTransform X_CT;
  Eigen::VectorXd erosion;
};

struct Refined {
  State state;
  double cost = std::numeric_limits<double>::infinity();  // sum of squared residuals
  int iterations = 0;
};

// Erosion at a corner: basis(corner) . coefficients. Global: {1}; affine: {1, u', v'} with
// u', v' the offset from the image centre over the image width; per tag: the indicator of
// the corner's edge group (coefficients in px).
class ErosionBasis {
 public:
  ErosionBasis(ErosionModel model, const CameraModel& camera,
               const std::vector<CornerObservation>& corners)
      : model_(model),
        centre_(0.5 * camera.width(), 0.5 * camera.height()),
        scale_(1.0 / std::max(camera.width(), 1)) {
    count_ = model == ErosionModel::kAffine ? 3 : model == ErosionModel::kGlobal ? 1 : 0;
    if (model == ErosionModel::kPerTag) {
      for (const CornerObservation& c : corners) {
        if (c.edge_group >= 0 && group_index_.emplace(c.edge_group, count_).second) ++count_;
      }
    }
  }
  int count() const { return count_; }
  // Basis function k at corner c.
  double At(const CornerObservation& c, int k) const {
    switch (model_) {
      case ErosionModel::kPerTag: {
        const auto it = group_index_.find(c.edge_group);
        return it != group_index_.end() && it->second == k ? 1.0 : 0.0;
      }
      case ErosionModel::kAffine:
        return k == 0 ? 1.0 : scale_ * (c.uv[k - 1] - centre_[k - 1]);
      default:
        return 1.0;
    }
  }

 private:
  ErosionModel model_;
  int count_ = 0;
  Eigen::Vector2d centre_;
  double scale_;
  std::map<int, int> group_index_;  // edge group -> coefficient (kPerTag)
};

// Residuals project(X_CT p_TQ) + e(uv) erosion_px - uv and their Jacobian by (pose
// perturbation as in ReprojectionResiduals, erosion coefficients).
bool Residuals(const std::vector<CornerObservation>& corners, const CameraModel& camera,
               const ErosionBasis& basis, const State& state, Eigen::VectorXd* r,
               Eigen::MatrixXd* J) {
  const auto n = static_cast<Eigen::Index>(corners.size());
  Eigen::MatrixXd J_pose;
  if (!ReprojectionResiduals(corners, camera, state.X_CT, r, J != nullptr ? &J_pose : nullptr)) {
    return false;
  }
  if (J != nullptr) {
    J->resize(2 * n, 6 + basis.count());
    J->leftCols<6>() = J_pose;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const CornerObservation& c = corners[static_cast<size_t>(i)];
    for (int k = 0; k < basis.count(); ++k) {
      const double b = basis.At(c, k);
      r->segment<2>(2 * i) += b * state.erosion[k] * c.erosion_px;
      if (J != nullptr) J->block<2, 1>(2 * i, 6 + k) = b * c.erosion_px;
    }
  }
  return true;
}

State Perturbed(const State& state, const Eigen::VectorXd& delta) {
  return {RigidTransform(state.X_CT.rotation() * So3Exp(delta.segment<3>(3)),
                         state.X_CT.translation() + delta.head<3>()),
          state.erosion + delta.tail(state.erosion.size())};
}

// Levenberg-Marquardt on the reprojection error with the analytic Jacobian.
Refined RefineLm(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                 const ErosionBasis& basis, State state, const PoseOptions& options) {
  Refined out;
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!Residuals(corners, camera, basis, state, &r, &J)) return out;
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool accepted = false;
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(J.cols());
    while (lambda < 1e10) {
      Eigen::MatrixXd A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12);
      delta = A.ldlt().solve(-g);
      if (!delta.allFinite()) break;
      const State candidate = Perturbed(state, delta);
      Eigen::VectorXd r_new;
      if (Residuals(corners, camera, basis, candidate, &r_new, nullptr) &&
          r_new.squaredNorm() <= cost) {
        state = candidate;
        cost = r_new.squaredNorm();
        lambda = std::max(lambda * 0.1, 1e-12);
        accepted = true;
        break;
      }
      lambda *= 10;
    }
    if (!accepted) break;
    Residuals(corners, camera, basis, state, &r, &J);
    if (delta.norm() < options.step_tolerance) break;
  }
  out.state = state;
  out.cost = cost;
  out.iterations = it;
  return out;
}

// The erosion model actually fitted: none unless enough corners carry a direction.
ErosionModel EffectiveErosionModel(const std::vector<CornerObservation>& corners,
                                   const PoseOptions& options) {
  int with_direction = 0;
  for (const CornerObservation& c : corners) {
    if (c.erosion_px.squaredNorm() > 0) ++with_direction;
  }
  return with_direction >= options.min_erosion_corners ? options.erosion : ErosionModel::kNone;
}

// Cluster-robust ("sandwich") covariance of the parameters: H^-1 (sum_g s_g s_g^T) H^-1
// with H = J^T J and s_g = J_g^T r_g the score of edge group g. The corners of a tag come
// from the same four fitted sides, so their errors are correlated (a side fitted off moves
// two corners together); sigma^2 H^-1 assumes independent corners and then understates the
// pose's uncertainty. Corners outside any group count as groups of one. The factor
// G / (G - 1) * (n - 1) / (n - p) is the usual small-sample correction.
Eigen::MatrixXd EdgeGroupCovariance(const std::vector<CornerObservation>& corners,
                                    const Eigen::MatrixXd& H_inverse, const Eigen::MatrixXd& J,
                                    const Eigen::VectorXd& r) {
  const Eigen::Index p = J.cols();
  std::vector<std::pair<int, Eigen::Index>> group_of;  // (group, corner index), sorted
  for (size_t i = 0; i < corners.size(); ++i) {
    const int group = corners[i].edge_group;
    group_of.emplace_back(group >= 0 ? group : -1 - static_cast<int>(i),
                          static_cast<Eigen::Index>(i));
  }
  std::sort(group_of.begin(), group_of.end());
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd score = Eigen::VectorXd::Zero(p);
  int groups = 0;
  for (size_t k = 0; k < group_of.size(); ++k) {
    const Eigen::Index i = group_of[k].second;
    score += J.middleRows(2 * i, 2).transpose() * r.segment<2>(2 * i);
    if (k + 1 == group_of.size() || group_of[k + 1].first != group_of[k].first) {
      meat += score * score.transpose();
      score.setZero();
      ++groups;
    }
  }
  const double n = static_cast<double>(r.size());
  const double correction = groups > 1 ? groups / (groups - 1.0) * (n - 1) / (n - p) : 1.0;
  return correction * H_inverse * meat * H_inverse;
}

// Covariance of the parameters from the edge fits' pixel noise: the corners of a tag are
// the intersections of its four fitted sides, so their errors are correlated (a side's
// angle noise moves its two corners in opposite directions, which the tag's centre hardly
// feels). With Sigma = N N^T per group (CornerNoisePx), the estimate's covariance is
// H^-1 J^T Sigma J H^-1. What the residuals show beyond that noise (bias of the edge model
// under blur or a response curve, corners without a noise model) is added as independent
// per coordinate: e^2 H^-1 with e^2 = max(0, |r|^2 - E|r|^2 - 2 s) / (m - p), where
// E|r|^2 = trace(Sigma) - trace(J H^-1 J^T Sigma) is what the noise alone would leave and
// s ~ sqrt(2 trace(Sigma^2)) its standard deviation: a residual sum within the noise's own
// spread is no evidence of more error (a tag's 8 noise sources make |r|^2 spread ~20 %).
// `excess_out`: e^2, px^2 per coordinate.
Eigen::MatrixXd EdgeNoiseCovariance(const std::vector<CornerObservation>& corners,
                                    const Eigen::MatrixXd& H_inverse, const Eigen::MatrixXd& J,
                                    const Eigen::VectorXd& r, double* excess_out) {
  const Eigen::Index p = J.cols();
  Eigen::MatrixXd propagated = Eigen::MatrixXd::Zero(p, p);
  double expected_rss = 0, rss_variance = 0;
  for (const std::vector<Eigen::Index>& group : CornersByEdgeGroup(corners)) {
    Eigen::MatrixXd score_by_noise = Eigen::MatrixXd::Zero(p, CornerNoisePx::ColsAtCompileTime);
    Eigen::Matrix<double, 8, 8> noise_gram = Eigen::Matrix<double, 8, 8>::Zero();
    for (const Eigen::Index i : group) {
      const CornerNoisePx& N = corners[static_cast<size_t>(i)].noise_px;
      score_by_noise += J.middleRows(2 * i, 2).transpose() * N;
      noise_gram += N.transpose() * N;
    }
    expected_rss += noise_gram.trace();
    rss_variance += 2.0 * noise_gram.squaredNorm();  // 2 trace(Sigma_g^2)
    const Eigen::MatrixXd parameters_by_noise = H_inverse * score_by_noise;
    propagated += parameters_by_noise * parameters_by_noise.transpose();
    expected_rss -= (score_by_noise.transpose() * parameters_by_noise).trace();
  }
  const double dof = static_cast<double>(r.size() - p);
  const double beyond_noise = r.squaredNorm() - expected_rss - 2.0 * std::sqrt(rss_variance);
  const double excess = dof > 0 ? std::max(0.0, beyond_noise) / dof : 0.0;
  *excess_out = excess;
  return propagated + excess * H_inverse;
}

// Fewer edge groups than this many per parameter: the cluster-robust estimate is too
// noisy (its rank is at most the group count), the residual one is used.
constexpr int kMinGroupsPerParameter = 3;

// Number of edge groups (a corner outside any group counts as one), or 0 when no corner
// is in a group: then the corners are independent and sigma^2 H^-1 is the better estimate.
int CountEdgeGroups(const std::vector<CornerObservation>& corners) {
  std::vector<int> ids;
  int singles = 0;
  for (const CornerObservation& c : corners) {
    if (c.edge_group < 0) {
      ++singles;
    } else {
      ids.push_back(c.edge_group);
    }
  }
  if (ids.empty()) return 0;
  std::sort(ids.begin(), ids.end());
  return singles + static_cast<int>(std::unique(ids.begin(), ids.end()) - ids.begin());
}

// Each corner's per-axis standard deviation under the noise the covariance was built from:
// with the edge noise, its own share of the edge fits' noise (trace(N N^T) / 2 per axis)
// plus the corners' own excess (corner_noise.h); otherwise the residuals' own sigma^2; then
// the floor. What travels with the pose (common/formats/README.md#board-corners-csv).
std::vector<double> CornerSigmas(const std::vector<CornerObservation>& corners, bool edge_noise,
                                 double independent_variance, double floor_px) {
  std::vector<double> sigmas;
  sigmas.reserve(corners.size());
  for (const CornerObservation& c : corners) {
    const double own = edge_noise ? c.noise_px.squaredNorm() / 2.0 : 0.0;
    sigmas.push_back(std::sqrt(own + independent_variance + floor_px * floor_px));
  }
  return sigmas;
}

// Each corner's displacement by the fitted erosion, e(uv) * erosion_px, and the erosion's
// share of its uncertainty: the corrected corner uv - shift carries the erosion
// coefficients' covariance (`erosion_covariance`) through the same basis, per axis. The
// shift is common to the pose's corners, so this variance is added to each corner's sigma
// (what a consumer that takes corners as independent can use) rather than dropped.
void CornerErosion(const std::vector<CornerObservation>& corners, const ErosionBasis& basis,
                   const Eigen::VectorXd& erosion, const Eigen::MatrixXd& erosion_covariance,
                   PoseEstimate* estimate) {
  estimate->corner_erosion_px.assign(corners.size(), Eigen::Vector2d::Zero());
  for (size_t i = 0; i < corners.size(); ++i) {
    const CornerObservation& c = corners[i];
    if (basis.count() == 0 || c.erosion_px.squaredNorm() == 0) continue;
    Eigen::RowVectorXd b(basis.count());
    for (int k = 0; k < basis.count(); ++k) b[k] = basis.At(c, k);
    estimate->corner_erosion_px[i] = b.dot(erosion) * c.erosion_px;
    const double variance = (b * erosion_covariance * b.transpose())(0, 0);
    double& sigma = estimate->corner_sigma_px[i];
    sigma = std::sqrt(sigma * sigma + std::max(0.0, variance) * c.erosion_px.squaredNorm() / 2.0);
  }
}

}  // namespace

bool ReprojectionResiduals(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                           const RigidTransform& X_CT, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  const auto n = static_cast<Eigen::Index>(corners.size());
  r->resize(2 * n);
  if (J != nullptr) J->resize(2 * n, 6);
  const Eigen::Matrix3d& R_CT = X_CT.rotation();
  for (Eigen::Index i = 0; i < n; ++i) {
    const CornerObservation& c = corners[static_cast<size_t>(i)];
    const Eigen::Vector3d p_CQ = X_CT * c.p_TQ;
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J_uv_p;
    if (!camera.Project(p_CQ, &uv, J != nullptr ? &J_uv_p : nullptr)) return false;
    r->segment<2>(2 * i) = uv - c.uv;
    if (J != nullptr) {
      // p_CQ = R_CT Exp(dr) p_TQ + p_CT + dt: d/d(dt) = I, d/d(dr) = -R_CT [p_TQ]x.
      J->block<2, 3>(2 * i, 0) = J_uv_p;
      J->block<2, 3>(2 * i, 3) = -J_uv_p * R_CT * Skew(c.p_TQ);
    }
  }
  return true;
}

namespace {

// Step 2: each start refined on the pixel reprojection error (with the erosion
// parameters); the refinements that ended with a finite cost.
std::vector<Refined> RefineEachStart(const std::vector<RigidTransform>& starts,
                                     const std::vector<CornerObservation>& corners,
                                     const CameraModel& camera, const ErosionBasis& basis,
                                     const PoseOptions& options) {
  std::vector<Refined> solutions;
  for (const RigidTransform& X_CT : starts) {
    const State start{X_CT, Eigen::VectorXd::Zero(basis.count())};
    Refined refined = RefineLm(corners, camera, basis, start, options);
    if (std::isfinite(refined.cost)) solutions.push_back(refined);
  }
  return solutions;
}

// Step 3: the lowest-cost solution, and the other one's RMS (how clearly IPPE's two-fold
// ambiguity was resolved; infinity when there was only one).
size_t KeepTheBest(const std::vector<Refined>& solutions, double residual_count,
                   PoseEstimate* estimate) {
  size_t best = 0;
  for (size_t k = 1; k < solutions.size(); ++k) {
    if (solutions[k].cost < solutions[best].cost) best = k;
  }
  estimate->alternative_rms_px = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < solutions.size(); ++k) {
    if (k != best) estimate->alternative_rms_px = std::sqrt(solutions[k].cost / residual_count);
  }
  const Refined& sol = solutions[best];
  estimate->X_CT = sol.state.X_CT;
  estimate->iterations = sol.iterations;
  estimate->rms_px = std::sqrt(sol.cost / residual_count);
  return best;
}

// Step 4: the covariance of the pose at the solution, marginal over the erosion (its
// uncertainty is propagated, not ignored), from the options' noise model plus the corner
// floor; and each corner's sigma. False when J^T J is singular (pose not observable).
bool FillCovariance(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                    const ErosionBasis& basis, const Refined& sol, const PoseOptions& options,
                    PoseEstimate* estimate) {
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  Residuals(corners, camera, basis, sol.state, &r, &J);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(J.transpose() * J);
  if (!lu.isInvertible()) return false;
  const double dof = static_cast<double>(r.size() - J.cols());
  const double sigma2 = dof > 0 ? sol.cost / dof : 0.0;
  const Eigen::MatrixXd H_inverse = lu.inverse();
  const bool clustered =
      options.covariance == CovarianceModel::kEdgeGroup &&
      CountEdgeGroups(corners) >= kMinGroupsPerParameter * static_cast<int>(J.cols());
  const bool edge_noise = options.covariance == CovarianceModel::kEdgeNoise;
  double excess = sigma2;  // kResidual and kEdgeGroup: the residuals' own sigma^2
  const Eigen::MatrixXd fitted = edge_noise ? EdgeNoiseCovariance(corners, H_inverse, J, r, &excess)
                                 : clustered ? EdgeGroupCovariance(corners, H_inverse, J, r)
                                             : (sigma2 * H_inverse).eval();
  const double erosion_px = basis.count() > 0 ? sol.state.erosion[0] : 0.0;
  const double floor_px =
      options.corner_floor_px + options.corner_floor_erosion_gain * erosion_px * erosion_px;
  const Eigen::MatrixXd full = fitted + floor_px * floor_px * H_inverse;
  estimate->covariance = full.topLeftCorner<6, 6>();
  estimate->covariance = 0.5 * (estimate->covariance + estimate->covariance.transpose()).eval();
  if (basis.count() > 0) {
    estimate->erosion_px = sol.state.erosion[0];
    estimate->erosion_sigma_px = std::sqrt(std::max(0.0, full(6, 6)));
  }
  estimate->sigma_t =
      std::sqrt(std::max(0.0, estimate->covariance.topLeftCorner<3, 3>().trace() / 3));
  estimate->sigma_r =
      std::sqrt(std::max(0.0, estimate->covariance.bottomRightCorner<3, 3>().trace() / 3));
  // The corners' own share of the excess: what a wrong camera file leaves is smooth over the
  // board and belongs to the camera, not to the corners (corner_noise.h).
  const double own = ExcessBeyondSmoothField(corners, J, r);
  const double corner_excess = own >= 0 ? std::min(own, excess) : excess;
  estimate->corner_sigma_px = CornerSigmas(corners, edge_noise, corner_excess, floor_px);
  const int k = basis.count();
  CornerErosion(corners, basis, sol.state.erosion, full.bottomRightCorner(k, k), estimate);
  return true;
}

}  // namespace

PoseEstimate EstimatePose(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                          const PoseOptions& options) {
  PoseEstimate estimate;
  estimate.corners = static_cast<int>(corners.size());
  if (estimate.corners < std::max(options.min_corners, 4)) {
    estimate.status = PoseEstimate::Status::kTooFewCorners;
    estimate.message =
        fmt::format("{} corners, need {}", estimate.corners, std::max(options.min_corners, 4));
    return estimate;
  }
  const ErosionBasis basis(EffectiveErosionModel(corners, options), camera, corners);
  const std::vector<Refined> solutions =
      RefineEachStart(IppePlanarStarts(corners, camera), corners, camera, basis, options);
  if (solutions.empty()) {
    estimate.message = "no pose: IPPE found no start or every refinement failed";
    return estimate;
  }
  const size_t best = KeepTheBest(solutions, 2.0 * estimate.corners, &estimate);
  estimate.erosion_parameters = basis.count();
  if (!FillCovariance(corners, camera, basis, solutions[best], options, &estimate)) {
    estimate.message = "degenerate corner layout: the pose is not observable";
    return estimate;
  }
  estimate.status = PoseEstimate::Status::kOk;
  return estimate;
}

}  // namespace h4::cam
