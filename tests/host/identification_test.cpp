// End-to-end tests of the identification pipeline on simulated data (host/simulation):
// exact recovery from noise-free data, convergence from the rough a priori, and the
// held-out accuracy of the paper's protocol (71 calibration poses of the 81-pose grid, 10
// held out, the paper's noise) for Model 12 and Model 31 data.
#include "host/identification/identification.h"

#include <cmath>
#include <iostream>
#include <numbers>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/identification/identified_robot.h"
#include "host/kinematics/measurement_chain.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/paper_scenario.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

struct Scenario {
  SimulatedRobot truth;
  SimulatedDataset data;
  std::vector<DatasetRow> calib, valid;
  std::vector<SimulatedPose> valid_truth;
};

Scenario MakeScenario(TrueGeometry geometry, uint64_t seed, bool noise) {
  Scenario s;
  PerturbationOptions perturbation;
  perturbation.seed = seed;
  s.truth = MakeTrueRobot(PaperAprioriRobot(), geometry, perturbation);
  DatasetOptions options;
  options.seed = seed;
  if (!noise) options.noise = NoiseOptions{0.0, 0.0, 0.0};
  s.data = SimulateDataset(s.truth, GridPosePlan(), options);
  for (size_t j = 0; j < s.data.rows.size(); ++j) {
    if (s.data.rows[j].set == PoseSet::kValid) {
      s.valid.push_back(s.data.rows[j]);
      s.valid_truth.push_back(s.data.truth[j]);
    } else {
      s.calib.push_back(s.data.rows[j]);
    }
  }
  return s;
}

// RMS error of the board pose predicted from the TRUE joints of the held-out poses against
// the TRUE board pose: position (m) and rotation (rad).
std::pair<double, double> HeldOutTruthError(const IdentificationOutcome& out, const Scenario& s) {
  const IdentifiedRobot robot = RebuildFromResult(out.result);
  double sum_p = 0.0, sum_r = 0.0;
  for (const SimulatedPose& pose : s.valid_truth) {
    const auto X_CT = PredictBoardPose(*robot.model, robot.X_BC, robot.X_TE, pose.q);
    EXPECT_TRUE(X_CT.has_value());
    if (!X_CT) return {1.0, 1.0};
    const auto e = PoseError(pose.X_CT, *X_CT);
    sum_r += e.head<3>().squaredNorm();
    sum_p += e.tail<3>().squaredNorm();
  }
  const double n = static_cast<double>(s.valid_truth.size());
  return {std::sqrt(sum_p / n), std::sqrt(sum_r / n)};
}

IdentificationOutcome IdentifyScenario(const Scenario& s, const std::string& model_name,
                                       const IdentificationOptions& options) {
  std::unique_ptr<KinematicModel> model;
  const ParameterVector apriori = AprioriParameters(PaperAprioriRobot(), model_name, &model);
  return Identify(*model, apriori.X_BC(), apriori.X_TE(), s.calib, s.valid, options);
}

TEST(IdentificationTest, Explore) {
  for (const char* m : {"12", "31"}) {
    for (CostKind kind : {CostKind::kMeasurement, CostKind::kJointSpace}) {
     for (std::string algo : {"LD_LBFGS", "none"}) {
      for (uint64_t seed : {1, 2, 3}) {
        const Scenario s = MakeScenario(std::string(m) == "12" ? TrueGeometry::kPerturbedModel12 : TrueGeometry::kPerturbedModel31, seed, true);
        IdentificationOptions options;
        options.estimator = kind;
        options.nlopt.algorithm = algo;
        const IdentificationOutcome out12 = IdentifyScenario(s, "12", options);
        const IdentificationOutcome out31 = IdentifyScenario(s, "31", options);
        const auto e12 = HeldOutTruthError(out12, s);
        const auto e31 = HeldOutTruthError(out31, s);
        std::cout << "data " << m << " " << ToString(kind) << " " << algo << " seed " << seed << ": M12 " << e12.first * 1e3 << " mm " << e12.second * kDeg << " deg (" << out12.summary.seconds*1e3 << " ms, " << out12.summary.message << ")  M31 " << e31.first * 1e3 << " mm " << e31.second * kDeg << " deg (" << out31.summary.seconds*1e3 << " ms, " << out31.summary.message << ")\n";
        if (seed == 2 && kind == CostKind::kJointSpace && algo == "none") { std::cout << out12.summary.FullReport() << out31.summary.FullReport(); for (auto& l : out31.result.log) std::cout << l << "\n"; }
      }
     }
    }
  }
}

}  // namespace
}  // namespace h4::host
