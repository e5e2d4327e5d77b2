// The IdentificationResult of an identified solution; see solution_summary.h.
#include "host/identification/solution_summary.h"

#include <cmath>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "common/units.h"
#include "host/identification/identified_robot.h"
#include "host/identification/robot_accuracy.h"

namespace h4::host {
namespace {

// The estimator's residuals and Jacobian at the solution: the last stage's when it has
// them, else evaluated; nullopt (with the reason in the log) when they cannot be.
std::optional<SolutionJacobian> EstimatorAtSolution(const SolutionToSummarise& s,
                                                    IdentificationCost* cost,
                                                    std::vector<std::string>* log) {
  if (s.at_solution != nullptr) return *s.at_solution;
  SolutionJacobian evaluated;
  std::string why;
  if (cost->Evaluate(s.p, &evaluated.r, &evaluated.J, &why)) return evaluated;
  log->push_back("no covariance: " + why);
  return std::nullopt;
}

// Identifiability re-checked at the solution (on rows consistent with it): reported in the
// log, the mask is not changed.
void RecheckIdentifiability(const SolutionToSummarise& s, const Eigen::MatrixXd& J,
                            std::vector<std::string>* log) {
  ParameterVector check = s.p;
  IdentificationCost consistent(s.options.estimator, s.model, ConsistentRows(s.model, s.p, s.calib),
                                s.options.cost);
  Eigen::VectorXd r_check;
  Eigen::MatrixXd J_check;
  if (!consistent.Evaluate(s.p, &r_check, &J_check)) J_check = J;
  const IdentifiabilityReport recheck =
      AnalyzeIdentifiability(J_check, s.model.kind(), s.options.identifiability, &check);
  for (const FixedByAnalysis& f : recheck.fixed) {
    log->push_back("at the solution, " + f.name + " is also " + f.reason);
  }
}

// The translation rows of the board-pose error on the calibration poses: the measurement
// cost's rows without their 1/sigma weights (evaluated when the estimator is another
// cost); nullopt when they cannot be evaluated.
std::optional<Eigen::MatrixXd> BoardPositionRows(const SolutionToSummarise& s,
                                                 const IdentificationCost& cost,
                                                 const Eigen::MatrixXd& J) {
  const Eigen::Index poses = static_cast<Eigen::Index>(s.calib.size());
  Eigen::MatrixXd J_p(3 * poses, J.cols());
  if (s.options.estimator == CostKind::kMeasurement) {
    for (Eigen::Index j = 0; j < poses; ++j) {
      const double w_t = cost.TranslationWeight(s.calib[static_cast<size_t>(j)]);
      J_p.middleRows<3>(3 * j) = J.middleRows<3>(6 * j + 3) / w_t;
    }
    return J_p;
  }
  CostOptions unit = s.options.cost;
  unit.use_dataset_sigmas = false;
  unit.default_sigma_t = unit.default_sigma_r = 1.0;
  IdentificationCost board(CostKind::kMeasurement, s.model, s.calib, unit);
  Eigen::VectorXd e;
  Eigen::MatrixXd J_e;
  if (!board.Evaluate(s.p, &e, &J_e)) return std::nullopt;
  for (Eigen::Index j = 0; j < poses; ++j) J_p.middleRows<3>(3 * j) = J_e.middleRows<3>(6 * j + 3);
  return J_p;
}

// The camera file's intrinsics_covariance in the covariance (camera_file_uncertainty.h),
// with the predicted accuracy it had without it in the log.
// True when the share was added.
bool AddCameraFileShare(const SolutionToSummarise& s, const IdentificationCost& cost,
                        const SolutionJacobian& at_solution, Uncertainty* u,
                        IdentificationResult* result) {
  const std::optional<double> without = PredictedRobotAccuracy(
      s.model, s.p, s.calib, *u, s.options.board_size_sigma.value_or(0.0));
  const CameraShare share =
      AddCameraFileUncertainty(s.p, at_solution.J, cost, s.calib, *s.options.camera_file, u);
  if (!share.added) {
    result->log.push_back(
        "camera file: no intrinsics_covariance (or no pose it could be propagated to): the "
        "covariance assumes the intrinsics exact");
    return false;
  }
  result->log.push_back(fmt::format(
      "camera file: its intrinsics_covariance, shared by all {} poses, is in the covariance "
      "(predicted robot accuracy {:.4f} mm without it)",
      share.poses, 1e3 * without.value_or(NAN)));
  return true;
}

// Covariance figures: condition number, correlations, the chi2 line, and the position
// accuracy the covariance predicts for the board on the calibration poses.
void FillCovarianceFigures(const SolutionToSummarise& s, const IdentificationCost& cost,
                           const Eigen::MatrixXd& J, const Uncertainty& u,
                           IdentificationResult* result) {
  result->condition_number = u.condition_number;
  result->correlations = u.correlations;
  result->log.push_back(fmt::format("chi2/dof {:.4g}, sigma^2 {:.4g}, condition number {:.4g}",
                                    u.chi2_per_dof, u.sigma2, u.condition_number));
  const std::optional<Eigen::MatrixXd> J_p = BoardPositionRows(s, cost, J);
  if (J_p) result->predicted_position_accuracy_m = PredictedPositionAccuracy(u, *J_p);
  result->predicted_robot_accuracy_m =
      PredictedRobotAccuracy(s.model, s.p, s.calib, u, s.options.board_size_sigma.value_or(0.0));
}

// One row per parameter: value, a priori, one sigma when free and the covariance exists;
// the fixed ones also listed with their reasons.
void FillParameterRows(const SolutionToSummarise& s, const Uncertainty& u,
                       IdentificationResult* result) {
  result->parameters.clear();
  result->fixed.clear();
  for (int k = 0; k < s.p.size(); ++k) {
    ResultParameter rp;
    rp.name = s.p.names()[static_cast<size_t>(k)];
    rp.value = s.p.values()[k];
    rp.apriori = s.apriori.values()[k];
    rp.fixed = !s.p.is_free(k);
    if (rp.fixed) {
      result->fixed.push_back({rp.name, s.p.fixed_reason(k)});
    } else if (u.ok) {
      for (size_t f = 0; f < u.free_indices.size(); ++f) {
        if (u.free_indices[f] == k) rp.std = u.std[static_cast<Eigen::Index>(f)];
      }
    }
    result->parameters.push_back(rp);
  }
}

// The covariance of the free parameters spread over every parameter in the result's order
// (common/formats/README.md `parameter_covariance`): zero rows and columns for fixed ones,
// symmetrised against the rounding of the inverse.
Eigen::MatrixXd OverEveryParameter(const SolutionToSummarise& s, const std::vector<int>& free,
                                   const Eigen::MatrixXd& covariance) {
  const Eigen::Index n = s.p.size();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (size_t a = 0; a < free.size(); ++a) {
    for (size_t b = 0; b < free.size(); ++b) {
      const auto ia = static_cast<Eigen::Index>(a), ib = static_cast<Eigen::Index>(b);
      C(free[a], free[b]) = 0.5 * (covariance(ia, ib) + covariance(ib, ia));
    }
  }
  return C;
}

void FillParameterCovariance(const SolutionToSummarise& s, const Uncertainty& u,
                             const std::optional<Eigen::MatrixXd>& camera_exact,
                             IdentificationResult* result) {
  result->parameter_covariance.reset();
  result->parameter_covariance_camera_exact.reset();
  if (!u.ok) return;
  result->parameter_covariance = OverEveryParameter(s, u.free_indices, u.covariance);
  if (camera_exact) {
    result->parameter_covariance_camera_exact =
        OverEveryParameter(s, u.free_indices, *camera_exact);
  }
}

// Joint residuals on the calibration and held-out poses, and the held-out board pose error
// of the identified robot.
void FillResidualFigures(const SolutionToSummarise& s, IdentificationResult* result) {
  std::unique_ptr<KinematicModel> identified = s.model.Clone();
  s.p.ApplyTo(identified.get());
  int unreachable = 0;
  result->calib_rms_rad =
      JointResidualRms(*identified, result->X_BC, result->X_TE, s.calib, &unreachable);
  if (unreachable > 0)
    result->log.push_back(fmt::format("{} calibration poses out of reach", unreachable));
  result->valid_rms_rad =
      JointResidualRms(*identified, result->X_BC, result->X_TE, s.valid, &unreachable);
  if (unreachable > 0)
    result->log.push_back(fmt::format("{} validation poses out of reach", unreachable));
  if (s.valid.empty()) return;
  const BoardPoseErrors held_out =
      BoardPoseErrorsOf(*identified, result->X_BC, result->X_TE, s.valid);
  if (held_out.poses == 0) return;
  result->valid_position_rms_m = held_out.position_rms;
  result->valid_rotation_rms_rad = held_out.rotation_rms;
  result->log.push_back(fmt::format(
      "held-out board pose error RMS {:.4f} mm, {:.4f} deg over {} poses",
      held_out.position_rms * 1e3, DegreesFromRadians(held_out.rotation_rms), held_out.poses));
}

void FillPoseLists(const SolutionToSummarise& s, IdentificationResult* result) {
  result->calib_poses.clear();
  result->valid_poses.clear();
  for (const DatasetRow& row : s.calib) result->calib_poses.push_back(row.pose_id);
  for (const DatasetRow& row : s.valid) result->valid_poses.push_back(row.pose_id);
  result->rejected_poses = s.rejected;
}

}  // namespace

void SummariseSolution(const SolutionToSummarise& s, IdentificationOutcome* out) {
  IdentificationResult& result = out->result;
  result.model = s.model.kind();
  result.estimator = ToString(s.options.estimator);
  result.X_BC = s.p.X_BC();
  result.X_TE = s.p.X_TE();
  IdentificationCost cost(s.options.estimator, s.model, s.calib, s.options.cost);
  const std::optional<SolutionJacobian> at_solution = EstimatorAtSolution(s, &cost, &result.log);
  std::optional<Eigen::MatrixXd> camera_exact;  ///< the covariance before the file's share
  if (at_solution) {
    out->uncertainty = ComputeUncertainty(s.p, at_solution->r, at_solution->J,
                                          s.options.estimator == CostKind::kMeasurement,
                                          s.options.correlation_threshold);
    RecheckIdentifiability(s, at_solution->J, &result.log);
    if (out->uncertainty.ok && s.options.camera_file) {
      const Eigen::MatrixXd before = out->uncertainty.covariance;
      if (AddCameraFileShare(s, cost, *at_solution, &out->uncertainty, &result)) {
        camera_exact = before;
      }
    }
    if (out->uncertainty.ok)
      FillCovarianceFigures(s, cost, at_solution->J, out->uncertainty, &result);
  }
  FillParameterRows(s, out->uncertainty, &result);
  FillParameterCovariance(s, out->uncertainty, camera_exact, &result);
  FillResidualFigures(s, &result);
  FillPoseLists(s, &result);
}

}  // namespace h4::host
