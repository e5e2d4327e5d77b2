// The square's control law (control_law.h): a Model 31 driven with poses planned in B sends
// the joints Model 12 would for the same robot, not those of the pose taken in B31.
#include "host/campaign/control_law.h"

#include <gtest/gtest.h>

#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host {
namespace {

TEST(ControlLaw, AModel31TakesThePlannedPosesInBThroughX_B31B) {
  const RobotDescription apriori = PaperAprioriRobot();
  const auto model12 = std::make_shared<Model12>(apriori.model12, apriori.assembly);
  const auto model31 = std::make_shared<Model31>(NominalModel31(apriori.model12), apriori.assembly);
  const ControlLawFunction law12 = InverseKinematicsControlLaw(model12, std::nullopt);
  const ControlLawFunction law31 =
      InverseKinematicsControlLaw(model31, NominalX_B31B(apriori.model12));
  for (const PlannedPose& pose : GridPosePlan()) {
    const EePose& x_B = pose.x;
    std::string why;
    const std::optional<JointVector> q12 = law12(x_B, &why);
    const std::optional<JointVector> q31 = law31(x_B, &why);
    ASSERT_TRUE(q12 && q31) << why;
    EXPECT_LT((*q12 - *q31).cwiseAbs().maxCoeff(), 1e-9) << x_B.transpose();
  }
}

TEST(ControlLaw, AModel31WithoutX_B31BIsRefused) {
  const RobotDescription apriori = PaperAprioriRobot();
  const auto model31 = std::make_shared<Model31>(NominalModel31(apriori.model12), apriori.assembly);
  EXPECT_THROW(InverseKinematicsControlLaw(model31, std::nullopt), std::invalid_argument);
}

TEST(ControlLaw, APoseOutOfReachSaysSo) {
  const RobotDescription apriori = PaperAprioriRobot();
  const auto model12 = std::make_shared<Model12>(apriori.model12, apriori.assembly);
  std::string why;
  EXPECT_FALSE(InverseKinematicsControlLaw(model12, std::nullopt)(EePose(0, 0, -5.0, 0), &why));
  EXPECT_EQ(why, "inverse kinematics out of reach");
}

}  // namespace
}  // namespace h4::host
