// The checks of common/README.md ("Checks against the paper"): with Table 2's a priori and
// identified Model 12 parameters over the paper's 81-pose grid, the joint differences and
// the forward-kinematics pose error reproduce the paper's published figures (within 10%).
#include <cmath>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "common/units.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host {
namespace {

TEST(PaperChecks, GridHas81PosesOfThePaper) {
  const PosePlan plan = GridPosePlan();
  ASSERT_EQ(plan.size(), 81u);
  Eigen::Vector4d min = plan[0].x, max = plan[0].x, sum = Eigen::Vector4d::Zero();
  for (const auto& pose : plan) {
    min = min.cwiseMin(pose.x);
    max = max.cwiseMax(pose.x);
    sum += pose.x;
  }
  EXPECT_LT((max - min - Eigen::Vector4d(0.2, 0.2, 0.15, RadiansFromDegrees(40.0))).norm(), 1e-12);
  EXPECT_LT((sum / 81.0 - Eigen::Vector4d(0, 0, -0.45, 0)).norm(), 1e-12);
}

TEST(PaperChecks, AprioriJointErrorsMatchTable3BeforeCalibration) {
  const Model12 apriori(kPaperAprioriModel12);
  const Model12 truth(kPaperIdentifiedModel12);
  Eigen::Vector4d sum = Eigen::Vector4d::Zero(), sum_sq = Eigen::Vector4d::Zero();
  const PosePlan plan = GridPosePlan();
  for (const auto& pose : plan) {
    const IkResult q_apriori = apriori.InverseKinematics(pose.x);
    const IkResult q_true = truth.InverseKinematics(pose.x);
    ASSERT_TRUE(q_apriori.ok() && q_true.ok());
    for (int i = 0; i < 4; ++i) {
      const double e = WrapAngle(q_apriori.q[i] - q_true.q[i]);
      sum[i] += e;
      sum_sq[i] += e * e;
    }
  }
  const double n = static_cast<double>(plan.size());
  const Eigen::Vector4d mean = sum / n;
  const Eigen::Vector4d rms = (sum_sq / n).cwiseSqrt();
  const Eigen::Vector4d expected_mean(-0.094, -0.036, -0.075, -0.084);
  const Eigen::Vector4d expected_rms(0.094, 0.038, 0.076, 0.085);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(mean[i], expected_mean[i], 0.1 * std::abs(expected_mean[i])) << "joint " << i + 1;
    EXPECT_NEAR(rms[i], expected_rms[i], 0.1 * expected_rms[i]) << "joint " << i + 1;
  }
  std::cout << "mean " << mean.transpose() << " rms " << rms.transpose() << "\n";
}

TEST(PaperChecks, AprioriForwardKinematicsMissesByPaperAverage) {
  const Model12 apriori(kPaperAprioriModel12);
  const Model12 truth(kPaperIdentifiedModel12);
  double position_sum = 0.0, angle_sum = 0.0;
  const PosePlan plan = GridPosePlan();
  for (const auto& pose : plan) {
    const IkResult q_true = truth.InverseKinematics(pose.x);
    ASSERT_TRUE(q_true.ok());
    const FkResult fk = ForwardKinematics(apriori, q_true.q);
    ASSERT_TRUE(fk.ok()) << fk.message;
    position_sum += (fk.x.head<3>() - pose.x.head<3>()).norm();
    angle_sum += std::abs(WrapAngle(fk.x[3] - pose.x[3]));
  }
  const double n = static_cast<double>(plan.size());
  const double position_mean = position_sum / n, angle_mean = angle_sum / n;
  EXPECT_NEAR(position_mean, 0.026, 0.1 * 0.026);
  EXPECT_NEAR(angle_mean, 0.025, 0.1 * 0.025);
  std::cout << "mean position error " << position_mean * 1e3 << " mm, angle " << angle_mean
            << " rad\n";
}

}  // namespace
}  // namespace h4::host
