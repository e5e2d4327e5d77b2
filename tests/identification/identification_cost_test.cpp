// Tests of the identification costs (eq. (3), eq. (5), measurement space) and of the
// measurement-chain Jacobians they use: residuals vanish on noise-free data at the truth,
// and every analytic Jacobian matches central finite differences.
#include "host/identification/identification_cost.h"

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/pose_chain.h"
#include "host/kinematics/measurement_chain.h"
#include "tests/identification/identification_test_helpers.h"
#include "tests/kinematics/jacobian_check_helpers.h"

namespace h4::host {
namespace {

using testing::JacobianMatchesFiniteDifferences;
using testing::NoiseFreeRows;
using testing::TrueSetup;

// A parameter vector moved off the truth by a deterministic pattern (1e-3 relative units).
Eigen::VectorXd Perturbed(const Eigen::VectorXd& v, double amount) {
  Eigen::VectorXd out = v;
  for (Eigen::Index k = 0; k < v.size(); ++k) out[k] += amount * std::sin(1.7 * (k + 1));
  return out;
}

TEST(PoseChainTest, MeasuredPoseJacobiansMatchFiniteDifferences) {
  const RigidTransform X_CT = RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.02, -0.05, 0.55),
                                                                 Eigen::Vector3d(0.05, -0.03, 0.3));
  Eigen::VectorXd v0(12);
  v0 << 0.01, -0.02, -1.05, 0.02, -0.03, 0.1, 0.09, 0.08, 0.025, 0.01, 0.02, -0.05;
  auto chain = [&](const Eigen::VectorXd& v) {
    return EePoseFromMeasurementWithJacobians(TransformFromParameters(v.head<6>()), X_CT,
                                              TransformFromParameters(v.tail<6>()));
  };
  const MeasuredEePoseJacobians at0 = chain(v0);
  Eigen::MatrixXd J(4, 12);
  J << at0.J_x_bc, at0.J_x_te;
  const auto f = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return chain(v).x; };
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(f, v0, J, 1e-6, 1e-7));
  // The pose itself agrees with the kinematics' measurement chain.
  const EePose x_ref = EePoseFromMeasurement(TransformFromParameters(v0.head<6>()), X_CT,
                                             TransformFromParameters(v0.tail<6>()))
                           .x;
  EXPECT_LT((at0.x - x_ref).norm(), 1e-14);
}

TEST(PoseChainTest, BoardPoseErrorJacobiansMatchFiniteDifferences) {
  const RigidTransform X_CT_measured = RigidTransform::FromTranslationRpy(
      Eigen::Vector3d(0.03, -0.04, 0.6), Eigen::Vector3d(0.1, -0.05, 0.4));
  Eigen::VectorXd v0(16);
  v0 << 0.02, 0.03, -0.44, 0.35, 0.01, -0.02, -1.05, 0.02, -0.03, 0.1, 0.09, 0.08, 0.025, 0.01,
      0.02, -0.05;
  auto error = [&](const Eigen::VectorXd& v, bool jac) {
    return BoardPoseErrorOf(TransformFromParameters(v.segment<6>(4)), v.head<4>(),
                            TransformFromParameters(v.tail<6>()), X_CT_measured, jac);
  };
  const BoardPoseError at0 = error(v0, true);
  ASSERT_GT(at0.e.head<3>().norm(), 0.1);  // far enough from zero to exercise JrInv
  Eigen::MatrixXd J(6, 16);
  J << at0.J_e_x, at0.J_e_bc, at0.J_e_te;
  const auto f = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return error(v, false).e; };
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(f, v0, J, 1e-6, 1e-7));
}

struct CostCase {
  ModelKind model;
  CostKind kind;
};

class CostTest : public ::testing::TestWithParam<CostCase> {
 protected:
  TrueSetup Setup() const {
    return GetParam().model == ModelKind::k12 ? testing::TrueModel12Setup()
                                              : testing::TrueModel31Setup();
  }
};

TEST_P(CostTest, ResidualsVanishAtTheTruthOnNoiseFreeData) {
  const TrueSetup setup = Setup();
  IdentificationCost cost(GetParam().kind, *setup.model, NoiseFreeRows(setup));
  const ParameterVector p(*setup.model, setup.X_BC, setup.X_TE);
  Eigen::VectorXd r;
  std::string why;
  ASSERT_TRUE(cost.Evaluate(p, &r, nullptr, &why)) << why;
  EXPECT_EQ(r.size(), cost.residual_count());
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-9);
}

TEST_P(CostTest, WarmStartedEvaluationsMatchAFreshCost) {
  // The measurement cost starts forward kinematics from each pose's last solution: after
  // evaluating elsewhere, coming back must give what a fresh cost gives.
  const TrueSetup setup = Setup();
  const std::vector<DatasetRow> rows = NoiseFreeRows(setup);
  IdentificationCost cost(GetParam().kind, *setup.model, rows);
  const ParameterVector p(*setup.model, setup.X_BC, setup.X_TE);
  ParameterVector moved = p;
  Eigen::VectorXd values = p.values();
  values.head(p.kinematic_count()).array() += 1e-3;
  moved.set_values(values);
  Eigen::VectorXd r_fresh, r_moved, r_back;
  Eigen::MatrixXd J_fresh, J_back;
  ASSERT_TRUE(
      IdentificationCost(GetParam().kind, *setup.model, rows).Evaluate(p, &r_fresh, &J_fresh));
  ASSERT_TRUE(cost.Evaluate(p, &r_back, nullptr));
  ASSERT_TRUE(cost.Evaluate(moved, &r_moved, nullptr));
  EXPECT_GT((r_moved - r_fresh).norm(), 1e-6);  // it did move
  ASSERT_TRUE(cost.Evaluate(p, &r_back, &J_back));
  EXPECT_LT((r_back - r_fresh).cwiseAbs().maxCoeff(), 1e-7);  // 1/sigma weights: 2e-11 m
  EXPECT_LT((J_back - J_fresh).cwiseAbs().maxCoeff(), 1e-6 * J_fresh.cwiseAbs().maxCoeff());
}

TEST_P(CostTest, JacobianMatchesFiniteDifferencesOffTheTruth) {
  const TrueSetup setup = Setup();
  CostOptions unit_sigma;  // unweighted, so that FK's 1e-12 tolerance stays below FD noise
  unit_sigma.default_sigma_t = 1.0;
  unit_sigma.default_sigma_r = 1.0;
  std::vector<DatasetRow> rows = NoiseFreeRows(setup);
  rows.resize(12);
  IdentificationCost cost(GetParam().kind, *setup.model, rows, unit_sigma);
  ParameterVector p(*setup.model, setup.X_BC, setup.X_TE);
  const Eigen::VectorXd v0 = Perturbed(p.values(), 2e-3);
  p.set_values(v0);
  Eigen::VectorXd r0;
  Eigen::MatrixXd J;
  std::string why;
  ASSERT_TRUE(cost.Evaluate(p, &r0, &J, &why)) << why;
  EXPECT_GT(r0.cwiseAbs().maxCoeff(), 1e-5);
  const auto f = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    ParameterVector q = p;
    q.set_values(v);
    Eigen::VectorXd r;
    EXPECT_TRUE(cost.Evaluate(q, &r, nullptr));
    // Joint residuals are wrapped angles: keep them continuous around r0.
    for (Eigen::Index k = 0; k < r.size(); ++k) r[k] = r0[k] + WrapAngle(r[k] - r0[k]);
    return r;
  };
  EXPECT_TRUE(JacobianMatchesFiniteDifferences(f, v0, J, 1e-5, 1e-6));
}

INSTANTIATE_TEST_SUITE_P(AllCosts, CostTest,
                         ::testing::Values(CostCase{ModelKind::k12, CostKind::kJointSpace},
                                           CostCase{ModelKind::k12, CostKind::kImplicit},
                                           CostCase{ModelKind::k12, CostKind::kMeasurement},
                                           CostCase{ModelKind::k31, CostKind::kJointSpace},
                                           CostCase{ModelKind::k31, CostKind::kImplicit},
                                           CostCase{ModelKind::k31, CostKind::kMeasurement}),
                         [](const ::testing::TestParamInfo<CostCase>& param_info) {
                           return std::string("Model") + ToString(param_info.param.model) + "_" +
                                  ToString(param_info.param.kind);
                         });

TEST(CostKindTest, NamesRoundTripAndUnknownIsRejected) {
  EXPECT_EQ(ParseCostKind("measurement"), CostKind::kMeasurement);
  EXPECT_EQ(ParseCostKind("joint"), CostKind::kJointSpace);
  EXPECT_EQ(ParseCostKind("implicit"), CostKind::kImplicit);
  for (CostKind kind : {CostKind::kJointSpace, CostKind::kImplicit, CostKind::kMeasurement}) {
    EXPECT_EQ(ParseCostKind(ToString(kind)), kind);
  }
  EXPECT_FALSE(ParseCostKind("ceres"));
}

}  // namespace
}  // namespace h4::host
