// Tests of the identification parameter vector: names and layout, the free/fixed mask, the
// transform parameterisation (R = Rz Ry Rx), and the Model 12 -> Model 31 conversion.
#include "host/identification/parameter_vector.h"

#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

TEST(ParameterVectorTest, NamesAreTheModelsThenTheTwelveTransformParameters) {
  const Model12 model(kPaperIdentifiedModel12);
  const ParameterVector p(model, PaperX_BC(), PaperX_TE());
  ASSERT_EQ(p.size(), 25);
  EXPECT_EQ(p.names()[0], "h");
  EXPECT_EQ(p.names()[13], "X_BC.tx");
  EXPECT_EQ(p.names()[18], "X_BC.rz");
  EXPECT_EQ(p.names()[24], "X_TE.rz");
  EXPECT_EQ(p.IndexOf("X_TE.tz"), 21);
  EXPECT_EQ(p.IndexOf("nope"), -1);
  EXPECT_DOUBLE_EQ(p.values()[p.IndexOf("X_BC.tz")], -1.05);
  EXPECT_DOUBLE_EQ(p.values()[p.IndexOf("forearm")], 0.4876);
}

TEST(ParameterVectorTest, TransformParametersAreTranslationThenRollPitchYaw) {
  const Vector6d v = (Vector6d() << 0.1, -0.2, 0.3, 0.05, -0.1, 0.7).finished();
  const RigidTransform X = TransformFromParameters(v);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).matrix() *
                            Eigen::AngleAxisd(-0.1, Eigen::Vector3d::UnitY()).matrix() *
                            Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()).matrix();
  EXPECT_LT((X.rotation() - R).norm(), 1e-15);
  EXPECT_LT((TransformToParameters(X) - v).norm(), 1e-14);
}

TEST(ParameterVectorTest, FixingKeepsValuesAndReasonsAndPacksTheFreeOnes) {
  const Model12 model(kPaperIdentifiedModel12);
  ParameterVector p(model, PaperX_BC(), PaperX_TE());
  p.Fix(p.IndexOf("d"), "no effect");
  p.Fix(p.IndexOf("X_TE.tz"), "sum with X_BC.tz");
  EXPECT_EQ(p.free_count(), 23);
  EXPECT_FALSE(p.is_free(p.IndexOf("d")));
  EXPECT_EQ(p.fixed_reason(p.IndexOf("d")), "no effect");
  Eigen::VectorXd v = p.FreeValues();
  v.setConstant(0.5);
  p.SetFreeValues(v);
  EXPECT_DOUBLE_EQ(p.values()[p.IndexOf("X_TE.tz")], 0.025);  // fixed: untouched
  EXPECT_DOUBLE_EQ(p.values()[p.IndexOf("h")], 0.5);
  p.FreeAll();
  EXPECT_EQ(p.free_count(), 25);
}

TEST(ParameterVectorTest, Model31ConversionPredictsTheSameBoardPoses) {
  Model12 model12(kPaperIdentifiedModel12);
  const RigidTransform X_BC = RigidTransform::FromTranslationRpy(
      Eigen::Vector3d(0.01, -0.02, -1.04), Eigen::Vector3d(0.01, 0.02, 0.3));
  const ParameterVector p12(model12, X_BC, PaperX_TE());
  Model31 model31(Model31Parameters{});
  const ParameterVector p31 = ConvertModel12To31(p12, &model31);
  ASSERT_EQ(p31.size(), 43);
  EXPECT_DOUBLE_EQ(p31.values()[p31.IndexOf("beta2")], -std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(p31.values()[p31.IndexOf("arm3")], kPaperIdentifiedModel12.arm);
  // The same joints give the same board pose through either model and its camera pose.
  const EePose x_B(0.05, -0.03, -0.42, 0.2);
  const IkResult ik = model12.InverseKinematics(x_B);
  ASSERT_TRUE(ik.ok());
  const RigidTransform X_CT_12 = PredictedBoardPose(p12.X_BC(), x_B, p12.X_TE());
  const EePose x_31 = EePoseFromMeasurement(p31.X_BC(), X_CT_12, p31.X_TE()).x;
  const IkResult ik31 = model31.InverseKinematics(x_31);
  ASSERT_TRUE(ik31.ok());
  EXPECT_LT((ik31.q - ik.q).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace h4::host
