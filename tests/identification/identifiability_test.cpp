// Tests of the identifiability analysis: on the paper's 81-pose grid it must find the
// paper's unidentifiable parameters (Model 12: X_TE.tz, X_TE.rx, X_TE.ry, d under eq. (3))
// and, for Model 31, d and one angle about z_B.
#include "host/identification/identifiability.h"

#include <algorithm>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "host/identification/identification.h"
#include "host/identification/identification_cost.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "tests/identification/identification_test_helpers.h"

namespace h4::host {
namespace {

std::vector<std::string> FixedNames(const IdentifiabilityReport& report) {
  std::vector<std::string> names;
  for (const FixedByAnalysis& f : report.fixed) names.push_back(f.name);
  std::sort(names.begin(), names.end());
  return names;
}

// The analysis at an identification's start point: the true kinematics with the a priori
// (untilted) board placement, on rows made consistent with it as the pipeline does.
IdentifiabilityReport Analyze(const testing::TrueSetup& setup, CostKind kind) {
  ParameterVector p(*setup.model, setup.X_BC, PaperX_TE());
  const std::vector<DatasetRow> rows =
      ConsistentRows(*setup.model, p, testing::NoiseFreeRows(setup));
  IdentificationCost cost(kind, *setup.model, rows);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  EXPECT_TRUE(cost.Evaluate(p, &r, &J));
  const IdentifiabilityReport report = AnalyzeIdentifiability(J, setup.model->kind(), {}, &p);
  for (const std::string& line : report.log) std::cout << "  " << line << "\n";
  return report;
}

TEST(IdentifiabilityTest, Model12JointSpaceFixesThePapersSet) {
  const IdentifiabilityReport report = Analyze(testing::TrueModel12Setup(), CostKind::kJointSpace);
  EXPECT_EQ(FixedNames(report), (std::vector<std::string>{"X_TE.rx", "X_TE.ry", "X_TE.tz", "d"}));
  EXPECT_LT(report.condition_number, 1e4);
}

TEST(IdentifiabilityTest, Model12MeasurementSpaceAlsoIdentifiesTheBoardTilt) {
  // The rotation residuals see the board tilt at first order: only the X_BC.tz / X_TE.tz sum
  // and the inert d remain.
  const IdentifiabilityReport report = Analyze(testing::TrueModel12Setup(), CostKind::kMeasurement);
  EXPECT_EQ(FixedNames(report), (std::vector<std::string>{"X_TE.tz", "d"}));
}

TEST(IdentifiabilityTest, Model31FixesDAndAnAngleAboutZbNotTheBoardAngle) {
  // common/README.md: fixing X_TE.rz (the paper's choice) leaves a null direction made of
  // X_BC.rz and the base joints; the analysis must fix X_BC.rz instead.
  for (CostKind kind : {CostKind::kJointSpace, CostKind::kImplicit, CostKind::kMeasurement}) {
    const std::vector<std::string> fixed = FixedNames(Analyze(testing::TrueModel31Setup(), kind));
    for (const char* name : {"X_BC.rz", "X_TE.tz", "d"}) {
      EXPECT_NE(std::find(fixed.begin(), fixed.end(), name), fixed.end())
          << ToString(kind) << " " << name;
    }
    EXPECT_EQ(std::find(fixed.begin(), fixed.end(), "X_TE.rz"), fixed.end()) << ToString(kind);
  }
}

TEST(IdentifiabilityTest, AFullRankJacobianFixesNothing) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Random(40, 25);
  const Model12 model(Model12Parameters{});
  ParameterVector p(model, PaperX_BC(), PaperX_TE());
  const IdentifiabilityReport report = AnalyzeIdentifiability(J, ModelKind::k12, {}, &p);
  EXPECT_TRUE(report.fixed.empty());
  EXPECT_EQ(p.free_count(), 25);
}

// issue 27 point 5: a robot.yaml with h = 1e154 gave a Jacobian holding inf and NaN, on
// which every round found a null direction and fixed nothing: `identify` never ended. The
// analysis refuses such a Jacobian, and ends either way.
TEST(IdentifiabilityTest, ANonFiniteJacobianIsRefusedNotLoopedOn) {
  const testing::TrueSetup setup = testing::TrueModel12Setup();
  ParameterVector p(*setup.model, setup.X_BC, PaperX_TE());
  IdentificationCost cost(CostKind::kMeasurement, *setup.model,
                          ConsistentRows(*setup.model, p, testing::NoiseFreeRows(setup)));
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  ASSERT_TRUE(cost.Evaluate(p, &r, &J));
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Eigen::MatrixXd J_bad = J;
    J_bad.col(0).setConstant(bad);
    ParameterVector q = p;
    try {
      AnalyzeIdentifiability(J_bad, setup.model->kind(), {}, &q);
      ADD_FAILURE() << "a Jacobian holding " << bad << " was analysed";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("inf or NaN"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace h4::host
