// Result filling and the summary report; see identification_report.h.
#include "host/identification/identification_report.h"

#include <cstdio>
#include <sstream>

#include "host/identification/identified_robot.h"

namespace h4::host {
namespace {

std::string Printf(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c, d);
  return buffer;
}

}  // namespace

void FillResult(const KinematicModel& model, const ParameterVector& apriori,
                const ParameterVector& p, const std::vector<DatasetRow>& calib,
                const std::vector<DatasetRow>& valid, const std::vector<int64_t>& rejected,
                const IdentificationOptions& options, IdentificationOutcome* out,
                const SolutionJacobian* at_solution) {
  IdentificationResult& result = out->result;
  result.model = model.kind();
  result.estimator = ToString(options.estimator);
  result.X_BC = p.X_BC();
  result.X_TE = p.X_TE();

  // Covariance of the estimator's cost at the solution.
  const IdentificationCost cost(options.estimator, model, calib, options.cost);
  SolutionJacobian evaluated;
  std::string why;
  const bool have_jacobian =
      at_solution != nullptr || cost.Evaluate(p, &evaluated.r, &evaluated.J, &why);
  const Eigen::VectorXd& r = at_solution != nullptr ? at_solution->r : evaluated.r;
  const Eigen::MatrixXd& J = at_solution != nullptr ? at_solution->J : evaluated.J;
  if (have_jacobian) {
    out->uncertainty = ComputeUncertainty(p, r, J, options.estimator == CostKind::kMeasurement,
                                          options.correlation_threshold);
    // Re-check of identifiability at the solution: report, do not change the mask.
    ParameterVector check = p;
    const IdentificationCost consistent(options.estimator, model, ConsistentRows(model, p, calib),
                                        options.cost);
    Eigen::VectorXd r_check;
    Eigen::MatrixXd J_check;
    if (!consistent.Evaluate(p, &r_check, &J_check)) J_check = J;
    const IdentifiabilityReport recheck =
        AnalyzeIdentifiability(J_check, model.kind(), options.identifiability, &check);
    for (const FixedByAnalysis& f : recheck.fixed) {
      result.log.push_back("at the solution, " + f.name + " is also " + f.reason);
    }
  } else {
    result.log.push_back("no covariance: " + why);
  }
  const Uncertainty& u = out->uncertainty;
  if (u.ok) {
    result.condition_number = u.condition_number;
    result.correlations = u.correlations;
    result.log.push_back(Printf("chi2/dof %.4g, sigma^2 %.4g, condition number %.4g",
                                u.chi2_per_dof, u.sigma2, u.condition_number));
    // Position accuracy the covariance predicts for the board on the calibration poses:
    // the translation rows of the board-pose error, i.e. the measurement cost's rows
    // without their 1/sigma weights (evaluated when the estimator is another cost).
    const Eigen::Index poses = static_cast<Eigen::Index>(calib.size());
    Eigen::MatrixXd J_p(3 * poses, J.cols());
    bool have_position_rows = false;
    if (options.estimator == CostKind::kMeasurement) {
      for (Eigen::Index j = 0; j < poses; ++j) {
        const double w_t = cost.TranslationWeight(calib[static_cast<size_t>(j)]);
        J_p.middleRows<3>(3 * j) = J.middleRows<3>(6 * j + 3) / w_t;
      }
      have_position_rows = true;
    } else {
      CostOptions unit = options.cost;
      unit.use_dataset_sigmas = false;
      unit.default_sigma_t = unit.default_sigma_r = 1.0;
      const IdentificationCost board(CostKind::kMeasurement, model, calib, unit);
      Eigen::VectorXd e;
      Eigen::MatrixXd J_e;
      if (board.Evaluate(p, &e, &J_e)) {
        for (Eigen::Index j = 0; j < poses; ++j)
          J_p.middleRows<3>(3 * j) = J_e.middleRows<3>(6 * j + 3);
        have_position_rows = true;
      }
    }
    if (have_position_rows) {
      result.predicted_position_accuracy_m = PredictedPositionAccuracy(u, J_p);
    }
  }

  result.parameters.clear();
  result.fixed.clear();
  for (int k = 0; k < p.size(); ++k) {
    ResultParameter rp;
    rp.name = p.names()[static_cast<size_t>(k)];
    rp.value = p.values()[k];
    rp.apriori = apriori.values()[k];
    rp.fixed = !p.is_free(k);
    if (rp.fixed) {
      result.fixed.push_back({rp.name, p.fixed_reason(k)});
    } else if (u.ok) {
      for (size_t f = 0; f < u.free_indices.size(); ++f) {
        if (u.free_indices[f] == k) rp.std = u.std[static_cast<Eigen::Index>(f)];
      }
    }
    result.parameters.push_back(rp);
  }

  std::unique_ptr<KinematicModel> identified = model.Clone();
  p.ApplyTo(identified.get());
  int unreachable = 0;
  result.calib_rms_rad =
      JointResidualRms(*identified, result.X_BC, result.X_TE, calib, &unreachable);
  if (unreachable > 0)
    result.log.push_back(std::to_string(unreachable) + " calibration poses out of reach");
  result.valid_rms_rad =
      JointResidualRms(*identified, result.X_BC, result.X_TE, valid, &unreachable);
  if (unreachable > 0)
    result.log.push_back(std::to_string(unreachable) + " validation poses out of reach");
  if (!valid.empty()) {
    const BoardPoseErrors held_out =
        BoardPoseErrorsOf(*identified, result.X_BC, result.X_TE, valid);
    if (held_out.poses > 0) {
      result.valid_position_rms_m = held_out.position_rms;
      result.valid_rotation_rms_rad = held_out.rotation_rms;
      result.log.push_back(Printf("held-out board pose error RMS %.4f mm, %.4f deg over %.0f poses",
                                  held_out.position_rms * 1e3,
                                  held_out.rotation_rms * 57.29577951308232, held_out.poses));
    }
  }
  result.calib_poses.clear();
  result.valid_poses.clear();
  for (const DatasetRow& row : calib) result.calib_poses.push_back(row.pose_id);
  for (const DatasetRow& row : valid) result.valid_poses.push_back(row.pose_id);
  result.rejected_poses = rejected;
}

std::string IdentificationSummary::FullReport() const {
  std::ostringstream s;
  s << "identification: " << (usable ? "usable" : "NOT usable") << " (" << message << "), "
    << iterations << " iterations, " << Printf("%.3f s", seconds) << "\n";
  for (const StageSummary& stage : stages) {
    s << "stage " << stage.name << " on " << stage.poses << " poses: " << stage.message
      << Printf(", residual RMS %.6g -> %.6g\n", stage.rms_before, stage.rms_after);
    for (const std::string& f : stage.fixed) s << "  fixed " << f << "\n";
    for (const MinimizerReport& m : stage.minimizers) {
      s << "  " << m.name << ": " << m.iterations << " iterations, " << m.evaluations
        << " evaluations, cost " << Printf("%.6g -> %.6g", m.initial_cost, m.final_cost) << ", "
        << m.stop_reason << Printf(", %.2f ms\n", m.seconds * 1e3);
    }
  }
  s << Printf("final cost %.6g, chi2/dof %.4g\n", final_cost, chi2_per_dof);
  return s.str();
}

}  // namespace h4::host
