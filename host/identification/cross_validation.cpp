// k-fold cross-validation; see cross_validation.h. CrossValidate reads top-down: deal the
// poses into folds, refit without each fold from the full fit, score the fold's poses
// (their chi-square against the covariance a held-out residual has: the pose's noise plus
// the fold's parameter uncertainty at that pose).
#include "host/identification/cross_validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <random>

#include <Eigen/Cholesky>

#include "common/timing/clock.h"
#include "host/identification/identifiability.h"
#include "host/identification/identified_robot.h"

namespace h4::host {
namespace {

// fold[i] of row i: a seeded shuffle dealt round-robin, so fold sizes differ by one.
std::vector<int> DealIntoFolds(size_t rows, int folds, uint64_t seed) {
  std::vector<size_t> order(rows);
  std::iota(order.begin(), order.end(), size_t{0});
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<int> fold(rows);
  for (size_t k = 0; k < rows; ++k)
    fold[order[k]] = static_cast<int>(k % static_cast<size_t>(folds));
  return fold;
}

// The estimator refitted on `train` from the full fit (same mask), Levenberg-Marquardt
// alone: the full fit is already in its basin. False when it did not converge.
bool RefitWithout(const CrossValidationInputs& in, const std::vector<DatasetRow>& train,
                  ParameterVector* p) {
  IdentificationCost cost(in.estimator, in.model, train, in.cost);
  const ResidualFunction f = FreeParameterResiduals(&cost, *p);
  Eigen::VectorXd v = p->FreeValues();
  const MinimizerReport report = MinimizeWithLevenbergMarquardt(f, in.lm, &v);
  p->SetFreeValues(v);
  return report.converged;
}

// The fold's parameter uncertainty in the units of the normalised residuals: the normal
// matrix of the column-scaled measurement Jacobian on the training poses, factored.
struct FoldUncertainty {
  bool ok = false;
  Eigen::VectorXd scale;  ///< column norms of the free columns
  Eigen::LDLT<Eigen::MatrixXd> normal;
};

FoldUncertainty UncertaintyOf(const CrossValidationInputs& in, const std::vector<DatasetRow>& train,
                              const ParameterVector& p) {
  FoldUncertainty u;
  IdentificationCost measurement(CostKind::kMeasurement, in.model, train, in.cost);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (!measurement.Evaluate(p, &r, &J)) return u;
  const Eigen::MatrixXd J_free = FreeColumns(J, p);
  u.scale = ColumnScale(J_free);
  const Eigen::MatrixXd J_s = J_free * u.scale.cwiseInverse().asDiagonal();
  u.normal.compute(J_s.transpose() * J_s);
  // Fewer training residuals than free parameters (a fold of a handful of poses) leave the
  // normal matrix singular: its "uncertainty" is noise, and gave a chi-square of -441.
  u.ok = u.normal.info() == Eigen::Success && u.normal.isPositive() && J_s.rows() >= J_s.cols();
  return u;
}

// The held-out residual r (normalised by the pose's covariance) has covariance
// I + J C J^T: the pose's own noise plus the fold's parameter uncertainty, which is large
// at poses of high leverage (the grid's corners at extreme rotations). Its chi-square is
// r^T (I + J C J^T)^-1 r, 6 degrees of freedom when the model and the sigmas are right;
// r^T r when the fold's uncertainty cannot be computed.
double HeldOutChi2(const FoldUncertainty& u, const ParameterVector& p, const Eigen::VectorXd& r,
                   const Eigen::MatrixXd& J) {
  if (!u.ok) return r.squaredNorm();
  const Eigen::MatrixXd J_s = FreeColumns(J, p) * u.scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd S =
      Eigen::MatrixXd::Identity(r.size(), r.size()) + J_s * u.normal.solve(J_s.transpose());
  const double chi2 = r.dot(S.ldlt().solve(r));
  // S = I + PSD has every eigenvalue >= 1: a chi-square below 0 or above r^T r is rounding
  // in a near-singular fold, never a figure.
  return std::isfinite(chi2) && chi2 >= 0.0 ? std::min(chi2, r.squaredNorm()) : r.squaredNorm();
}

// One held-out pose predicted by the fold's parameters.
HeldOutPrediction Predict(const CrossValidationInputs& in, const ParameterVector& p,
                          const FoldUncertainty& u, const KinematicModel& robot,
                          const DatasetRow& row) {
  HeldOutPrediction prediction;
  prediction.pose_id = row.pose_id;
  const std::vector<DatasetRow> one{row};
  const BoardPoseErrors errors = BoardPoseErrorsOf(robot, p.X_BC(), p.X_TE(), one);
  IdentificationCost measurement(CostKind::kMeasurement, in.model, one, in.cost);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  if (errors.poses != 1 || !measurement.Evaluate(p, &r, &J)) return prediction;
  prediction.ok = true;
  prediction.position_error_m = errors.position_rms;
  prediction.rotation_error_rad = errors.rotation_rms;
  prediction.chi2 = HeldOutChi2(u, p, r, J);
  return prediction;
}

void Summarise(CrossValidation* cv) {
  double position = 0.0, rotation = 0.0, chi2 = 0.0;
  int predicted = 0;
  for (const HeldOutPrediction& pose : cv->poses) {
    if (!pose.ok) continue;
    position += pose.position_error_m * pose.position_error_m;
    rotation += pose.rotation_error_rad * pose.rotation_error_rad;
    chi2 += pose.chi2;
    ++predicted;
  }
  if (predicted == 0) return;
  cv->position_rms_m = std::sqrt(position / predicted);
  cv->rotation_rms_rad = std::sqrt(rotation / predicted);
  cv->reduced_chi2 = chi2 / (6.0 * predicted);
}

}  // namespace

bool CrossValidationOptions::IsValid(std::string* why) const {
  if (folds == 0 || folds >= 2) return true;
  if (why != nullptr) *why = "cross-validation folds must be 0 (off) or at least 2";
  return false;
}

CrossValidation CrossValidate(const CrossValidationInputs& in,
                              const CrossValidationOptions& options) {
  CrossValidation cv;
  if (options.folds < 2 || in.rows.size() < 2) return cv;
  const auto start = std::chrono::steady_clock::now();
  cv.folds = std::min(options.folds, static_cast<int>(in.rows.size()));
  const std::vector<int> fold = DealIntoFolds(in.rows.size(), cv.folds, options.seed);
  cv.poses.resize(in.rows.size());
  std::unique_ptr<KinematicModel> robot = in.model.Clone();
  for (int k = 0; k < cv.folds; ++k) {
    std::vector<DatasetRow> train;
    for (size_t i = 0; i < in.rows.size(); ++i) {
      if (fold[i] != k) train.push_back(in.rows[i]);
    }
    ParameterVector p = in.fit;
    if (!RefitWithout(in, train, &p)) ++cv.failed_folds;
    p.ApplyTo(robot.get());
    const FoldUncertainty u = UncertaintyOf(in, train, p);
    for (size_t i = 0; i < in.rows.size(); ++i) {
      if (fold[i] == k) cv.poses[i] = Predict(in, p, u, *robot, in.rows[i]);
    }
  }
  Summarise(&cv);
  cv.seconds = SecondsSince(start);
  return cv;
}

}  // namespace h4::host
