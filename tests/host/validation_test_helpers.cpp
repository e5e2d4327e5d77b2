// Fixtures of the validation and report tests (see validation_test_helpers.h).
#include "tests/host/validation_test_helpers.h"

#include "host/kinematics/model12.h"
#include "host/simulation/paper_scenario.h"
#include "host/simulation/pose_plan.h"

namespace h4::host {

SimulatedRobot PaperTruth() {
  return MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
}

IdentificationResult PerfectModel12Result(const SimulatedRobot& truth,
                                          const std::vector<int64_t>& valid) {
  IdentificationResult result;
  result.model = "12";
  const Eigen::VectorXd values = Model12::ToVector(truth.model12);
  const Eigen::VectorXd apriori = Model12::ToVector(PaperAprioriRobot().model12);
  for (size_t k = 0; k < Model12::ParameterNames().size(); ++k) {
    ResultParameter p;
    p.name = Model12::ParameterNames()[k];
    p.value = values[static_cast<int>(k)];
    p.apriori = apriori[static_cast<int>(k)];
    p.std = 1e-4;
    result.parameters.push_back(p);
  }
  result.X_BC = truth.X_BC;
  result.X_TE = truth.X_TE;
  result.valid_poses = valid;
  return result;
}

ValidationInputs PaperValidationInputs() {
  const SimulatedRobot truth = PaperTruth();
  DatasetOptions options;
  options.noise = {0.0, 0.0, 0.0};
  const SimulatedDataset dataset = SimulateDataset(truth, GridPosePlan(), options);
  ValidationInputs in;
  in.apriori = PaperAprioriRobot();
  in.rows = dataset.rows;
  in.dataset_name = "paper.csv";
  std::vector<int64_t> valid;
  for (const DatasetRow& row : dataset.rows) {
    if (row.set == PoseSet::kValid) valid.push_back(row.pose_id);
  }
  in.result12 = PerfectModel12Result(truth, valid);
  for (const RulerLine& line : PaperRulerLines()) {
    in.straightness.push_back(SimulateRulerRun(truth, line, 0.0, 1));
  }
  in.truth = SimulationTruth{truth, NoiseOptions{}, 1, 1};
  return in;
}

}  // namespace h4::host
