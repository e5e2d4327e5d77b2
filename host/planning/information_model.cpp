// The information model of pose planning (information_model.h).
#include "host/planning/information_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <spdlog/fmt/fmt.h>

#include "common/units.h"
#include "host/identification/identifiability.h"
#include "host/identification/identification.h"
#include "host/simulation/dataset_simulator.h"

namespace h4::host {
namespace {

std::vector<DatasetRow> NoiseFreeRows(const RobotDescription& robot,
                                      const std::vector<EePose>& poses_B,
                                      const std::vector<PoseSigma>& sigmas) {
  PosePlan plan;
  for (size_t j = 0; j < poses_B.size(); ++j) {
    plan.push_back({static_cast<int64_t>(j + 1), poses_B[j]});
  }
  DatasetOptions options;
  options.noise = NoiseOptions::None();
  options.valid_count = 0;
  options.fill_sigma = false;  // the cost's default sigmas weight the rows
  // The a priori robot as a noise-free truth: the rows are exactly what the a priori model
  // predicts (residuals zero, Jacobian at the a priori).
  SimulatedDataset data = SimulateDataset(SimulatedRobot::FromDescription(robot), plan, options);
  if (!data.unreachable.empty()) {
    // Named by where it is: the index into poses_B (candidates, then evaluation poses)
    // means nothing to the user (it read "pose 1926 of the 2006").
    const EePose& x = poses_B[static_cast<size_t>(data.unreachable.front() - 1)];
    throw std::runtime_error(fmt::format(
        "pose planning: the pose X={:.1f} Y={:.1f} Z={:.1f} mm theta={:.1f} deg is out of the a "
        "priori robot's reach",
        x[0] * 1e3, x[1] * 1e3, x[2] * 1e3, DegreesFromRadians(x[3])));
  }
  for (size_t j = 0; j < sigmas.size() && j < data.rows.size(); ++j) {
    data.rows[j].sigma_t = sigmas[j].t;
    data.rows[j].sigma_r = sigmas[j].r;
  }
  return std::move(data.rows);
}

}  // namespace

InformationModel BuildInformationModel(const RobotDescription& robot, ModelKind kind,
                                       const std::vector<EePose>& poses_B, int analysed_count,
                                       const CostOptions& cost_options,
                                       const std::vector<PoseSigma>& sigmas) {
  AprioriModel apriori = AprioriModelOf(robot, kind);
  IdentificationCost cost(CostKind::kMeasurement, *apriori.model,
                          NoiseFreeRows(robot, poses_B, sigmas), cost_options);
  Eigen::VectorXd r;
  Eigen::MatrixXd J_full;
  std::string why;
  if (!cost.Evaluate(apriori.parameters, &r, &J_full, &why)) {
    throw std::runtime_error("pose planning: the measurement cost fails: " + why);
  }
  ParameterVector& p = apriori.parameters;
  const IdentifiabilityReport report =
      AnalyzeIdentifiability(J_full.topRows(6 * static_cast<Eigen::Index>(analysed_count)), kind,
                             IdentifiabilityOptions{}, &p);

  InformationModel info;
  info.model = kind;
  for (const FixedByAnalysis& f : report.fixed) info.fixed.push_back(f.name + ": " + f.reason);
  for (int i : p.FreeIndices()) info.free_names.push_back(p.names()[static_cast<size_t>(i)]);
  info.J_scaled = FreeColumns(J_full, p);
  const Eigen::VectorXd column_norm =
      info.J_scaled.topRows(6 * static_cast<Eigen::Index>(analysed_count)).colwise().norm();
  for (Eigen::Index c = 0; c < info.J_scaled.cols(); ++c) {
    if (column_norm[c] > 0.0) info.J_scaled.col(c) /= column_norm[c];
  }
  info.sigma_t = cost_options.default_sigma_t;
  return info;
}

Eigen::MatrixXd InformationMatrix(const InformationModel& info, const std::vector<int>& chosen,
                                  double ridge) {
  const int k = info.parameter_count();
  Eigen::MatrixXd M = ridge * Eigen::MatrixXd::Identity(k, k);
  for (int j : chosen) M.noalias() += info.Block(j).transpose() * info.Block(j);
  return M;
}

double PredictedPositionRms(const InformationModel& info, const Eigen::MatrixXd& M,
                            const std::vector<int>& evaluated) {
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success || evaluated.empty()) {
    return std::numeric_limits<double>::infinity();
  }
  // The smallest eigenvalue relative to the largest says whether M^-1 means anything.
  const Eigen::VectorXd diag = llt.matrixL().toDenseMatrix().diagonal();
  if (diag.minCoeff() < 1e-7 * diag.maxCoeff()) return std::numeric_limits<double>::infinity();
  double sum_variance = 0.0;
  for (int j : evaluated) {
    // trace(T M^-1 T^T) = |L^-1 T^T|_F^2.
    const Eigen::MatrixXd T_t = info.Block(j).bottomRows(3).transpose();
    sum_variance += llt.matrixL().solve(T_t).squaredNorm();
  }
  return info.sigma_t * std::sqrt(sum_variance / static_cast<double>(evaluated.size()));
}

}  // namespace h4::host
