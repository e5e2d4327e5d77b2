// Tests of the simulated H4 controller (no bus): finite-speed motion, the settle dwell,
// pose targets through the a priori inverse kinematics, the true board pose of eq. (6),
// refused targets, idempotent resends and the encoder noise.
#include "host/campaign/simulated_controller.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "common/units.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/simulation/true_robot.h"
#include "tests/campaign/joint_test_helpers.h"
#include "tests/support/options_check.h"

namespace h4::host {
namespace {

constexpr double kDt = 0.01;  // s, the node's 100 Hz step

SimulatedRobot PaperTruthWithPlacement() {
  PerturbationOptions placement;
  placement.seed = 1;
  return MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2, placement);
}

class SimulatedControllerTest : public ::testing::Test {
 protected:
  SimulatedControllerTest()
      : apriori_(PaperAprioriRobot()),
        truth_(PaperTruthWithPlacement()),
        controller_(truth_, apriori_.model12, apriori_.assembly) {}

  // Steps until settled (or `limit_s`); returns the time taken, s.
  double StepUntilSettled(SimulatedController& controller, double limit_s = 30.0) {
    double t = 0.0;
    while (!controller.settled() && t < limit_s) {
      controller.Step(kDt);
      t += kDt;
    }
    return t;
  }

  RobotDescription apriori_;
  SimulatedRobot truth_;
  SimulatedController controller_;
};

TEST_F(SimulatedControllerTest, StartsSettledAtTheTrueHomeJointsWithNoPoseId) {
  const IkResult home =
      Model12(truth_.model12, truth_.assembly).InverseKinematics(EePose(0.0, 0.0, -0.45, 0.0));
  ASSERT_TRUE(home.ok());
  EXPECT_LT(MaxWrappedJointDifference(controller_.true_joints(), home.q), 1e-12);
  EXPECT_EQ(controller_.pose_id(), -1);
  EXPECT_TRUE(controller_.settled());
  EXPECT_FALSE(controller_.moving());
}

TEST_F(SimulatedControllerTest, MovesNoFasterThanTheJointSpeed) {
  const EePose target(0.10, -0.10, -0.375, 0.349);
  const TargetResult result = controller_.SetPoseTarget(3, target);
  ASSERT_TRUE(result.ok()) << result.reason;
  const double distance = MaxWrappedJointDifference(result.q_target, controller_.true_joints());
  ASSERT_GT(distance, 0.1);  // a real move, many steps long
  const double speed = controller_.options().joint_speed;
  double t = 0.0;
  while (controller_.moving() && t < 30.0) {
    const JointVector before = controller_.true_joints();
    controller_.Step(kDt);
    t += kDt;
    EXPECT_LE(MaxWrappedJointDifference(controller_.true_joints(), before), speed * kDt + 1e-12);
  }
  // The farthest joint moves at full speed the whole way: arrival at distance / speed.
  EXPECT_NEAR(t, distance / speed, kDt + 1e-9);
  EXPECT_LT(MaxWrappedJointDifference(controller_.true_joints(), result.q_target), 1e-15);
}

TEST_F(SimulatedControllerTest, SettlesOnlyAfterTheSettleTimeAtTheTarget) {
  ASSERT_TRUE(controller_.SetPoseTarget(4, EePose(0.05, 0.0, -0.45, 0.0)).ok());
  EXPECT_FALSE(controller_.settled());
  double t = 0.0, arrived = -1.0;
  while (!controller_.settled() && t < 30.0) {
    controller_.Step(kDt);
    t += kDt;
    if (arrived < 0.0 && !controller_.moving()) arrived = t;
    if (controller_.moving()) {
      EXPECT_FALSE(controller_.settled());
    }
  }
  ASSERT_GT(arrived, 0.0);
  const double dwell = t - arrived;
  // Arrival falls inside a step, so the dwell is settle_time rounded up to the next step.
  EXPECT_GE(dwell + kDt + 1e-9, controller_.options().settle_time);
  EXPECT_LE(dwell, controller_.options().settle_time + kDt + 1e-9);
  EXPECT_EQ(controller_.pose_id(), 4);
}

TEST_F(SimulatedControllerTest, PoseTargetEndsAtTheAprioriModelsJointsNotTheTrueOnes) {
  const EePose target(-0.08, 0.06, -0.50, -0.2);
  ASSERT_TRUE(controller_.SetPoseTarget(5, target).ok());
  StepUntilSettled(controller_);
  ASSERT_TRUE(controller_.settled());
  const IkResult apriori_ik =
      Model12(apriori_.model12, apriori_.assembly).InverseKinematics(target);
  const IkResult true_ik = Model12(truth_.model12, truth_.assembly).InverseKinematics(target);
  ASSERT_TRUE(apriori_ik.ok() && true_ik.ok());
  EXPECT_LT(MaxWrappedJointDifference(controller_.true_joints(), apriori_ik.q), 1e-12);
  // Table 2's a priori misses the truth by several centiradians (common/README.md).
  EXPECT_GT(MaxWrappedJointDifference(controller_.true_joints(), true_ik.q), 0.02);
  // So the true end-effector is not where the campaign asked (about 26 mm on average).
  EXPECT_GT((controller_.true_X_BE().translation() - target.head<3>()).norm(), 0.005);
}

TEST_F(SimulatedControllerTest, HomeBoardPoseIsTheTrueChainAtTheHomePose) {
  const RigidTransform expected = truth_.X_BC.inverse() *
                                  TransformFromEePose(EePose(0.0, 0.0, -0.45, 0.0)) *
                                  truth_.X_TE.inverse();
  EXPECT_TRUE(controller_.true_X_CT().IsNearlyEqualTo(expected, 1e-12, 1e-12));
}

// Eq. (6) read backwards, independently of the forward kinematics: X_BE = X_BC X_CT X_TE
// must be a 4-DoF pose whose true inverse kinematics gives the true joints.
void ExpectTrueChainAtTarget(const SimulatedRobot& truth, const RobotDescription& apriori,
                             const JointVector& q_target) {
  SimulatedController controller(truth, apriori.model12, apriori.assembly);
  ASSERT_TRUE(controller.SetJointTarget(8, q_target).ok());
  for (int k = 0; k < 3000 && !controller.settled(); ++k) controller.Step(kDt);
  ASSERT_TRUE(controller.settled());
  const MeasuredEePose measured =
      EePoseFromMeasurement(truth.X_BC, controller.true_X_CT(), truth.X_TE);
  EXPECT_LT(measured.tilt_angle, 1e-12);
  const RigidTransform X_ModelB = truth.X_ModelB();
  const IkResult ik = truth.MakeModel()->InverseKinematics(
      EePoseFromTransform(X_ModelB * TransformFromEePose(measured.x)));
  ASSERT_TRUE(ik.ok());
  EXPECT_LT(MaxWrappedJointDifference(ik.q, controller.true_joints()), 1e-9);
  EXPECT_LT(MaxWrappedJointDifference(ik.q, q_target), 1e-9);
}

TEST_F(SimulatedControllerTest, BoardPoseAtAJointTargetFollowsTheTrueChainModel12) {
  const IkResult ik =
      Model12(truth_.model12, truth_.assembly).InverseKinematics(EePose(0.07, 0.09, -0.40, 0.3));
  ASSERT_TRUE(ik.ok());
  ExpectTrueChainAtTarget(truth_, apriori_, ik.q);
}

TEST_F(SimulatedControllerTest, BoardPoseAtAJointTargetFollowsTheTrueChainModel31) {
  PerturbationOptions options;
  options.seed = 3;
  const SimulatedRobot truth31 = MakeTrueRobot(apriori_, TrueGeometry::kPerturbedModel31, options);
  ASSERT_TRUE(truth31.model31.has_value());
  // Joints of a pose in B, through B31 (the true model's frame).
  const EePose x_B(-0.09, 0.05, -0.52, -0.3);
  const IkResult ik = truth31.MakeModel()->InverseKinematics(
      EePoseFromTransform(truth31.X_ModelB() * TransformFromEePose(x_B)));
  ASSERT_TRUE(ik.ok());
  ExpectTrueChainAtTarget(truth31, apriori_, ik.q);
  SimulatedController controller(truth31, apriori_.model12, apriori_.assembly);
  ASSERT_TRUE(controller.SetJointTarget(1, ik.q).ok());
  for (int k = 0; k < 3000 && !controller.settled(); ++k) controller.Step(kDt);
  const RigidTransform expected =
      truth31.X_BC.inverse() * TransformFromEePose(x_B) * truth31.X_TE.inverse();
  EXPECT_TRUE(controller.true_X_CT().IsNearlyEqualTo(expected, 1e-9, 1e-9));
}

// Issue 27 point 11: live, on a plan's poses, the board yaw drifted away from the commanded
// theta (-40 deg gave -63, 10 gave -94, ...) while `h4cal simulate` stayed within 0.5 deg:
// the forward kinematics, continued from one step to the next, left its assembly branch
// along the way, where a late tick made a long step. The board pose a settled robot shows
// must depend on its joints only: the same target reached along a path of earlier poses or
// straight from home gives one pose, near the commanded one (Table 2's a priori misses
// theta by up to 0.57 rad on these poses, near the theta singularity; the drift reached
// pi). Before the fix, 61 of these poses differed from home's.
void ExpectSettledPosesIndependentOfThePath(const SimulatedRobot& truth,
                                            const RobotDescription& apriori, uint64_t seed) {
  SimulatedController controller(truth, apriori.model12, apriori.assembly);
  std::mt19937_64 rng(seed);
  // The node steps on the wall clock: a loaded host ticks late, and a step then moves the
  // joints a long way (0.5 rad/s x 0.3 s).
  std::uniform_real_distribution<double> tick(0.01, 0.3);
  // The candidate grid of `h4cal plan` (host/planning/candidate_poses.h).
  std::uniform_real_distribution<double> xy(-0.25, 0.25), z(-0.60, -0.30), theta(-1.05, 1.05);
  int compared = 0;
  for (int k = 0; k < 24; ++k) {
    const EePose target(xy(rng), xy(rng), z(rng), theta(rng));
    if (!controller.SetPoseTarget(k, target).ok()) continue;
    for (int step = 0; step < 3000 && !controller.settled(); ++step) controller.Step(tick(rng));
    ASSERT_TRUE(controller.settled()) << "pose " << k;
    SimulatedController from_home(truth, apriori.model12, apriori.assembly);
    ASSERT_TRUE(from_home.SetPoseTarget(k, target).ok());
    for (int step = 0; step < 3000 && !from_home.settled(); ++step) from_home.Step(kDt);
    ASSERT_TRUE(from_home.settled());
    ASSERT_LT(MaxWrappedJointDifference(controller.true_joints(), from_home.true_joints()), 1e-12);
    const RigidTransform& along_path = controller.true_X_BE();
    const double theta_along_path = EePoseFromTransform(along_path)[3];
    EXPECT_TRUE(along_path.IsNearlyEqualTo(from_home.true_X_BE(), 1e-9, 1e-9))
        << "pose " << k << ": reached along the path at theta " << theta_along_path
        << " rad, from home at " << EePoseFromTransform(from_home.true_X_BE())[3]
        << " rad, commanded " << target[3];
    EXPECT_LT(std::abs(WrapAngle(theta_along_path - target[3])), 0.7) << "pose " << k;
    EXPECT_LT((along_path.translation() - target.head<3>()).norm(), 0.1) << "pose " << k;
    ++compared;
  }
  EXPECT_GE(compared, 12);
}

TEST_F(SimulatedControllerTest, SettledPoseDoesNotDependOnThePathThereModel12) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    ExpectSettledPosesIndependentOfThePath(truth_, apriori_, seed);
  }
}

TEST_F(SimulatedControllerTest, SettledPoseDoesNotDependOnThePathThereModel31) {
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    PerturbationOptions options;
    options.seed = seed;
    const SimulatedRobot truth31 =
        MakeTrueRobot(apriori_, TrueGeometry::kPerturbedModel31, options);
    ExpectSettledPosesIndependentOfThePath(truth31, apriori_, seed);
  }
}

// The 24 poses `h4cal plan` chose for `h4cal simulate`'s robot (the demo camera and board),
// X, Y, Z in m and theta in deg, driven with ticks up to 0.3 s as on a loaded host: each pose
// the controller accepts is shown at the pose its joints give from home, near the commanded
// one. Five (-40 and -60 deg) are refused: at the joints the a priori robot sends there the
// true robot has no pose on its branch (none of 13 608 starts of the forward kinematics
// converged on it), before the fix as after.
TEST(SimulatedControllerPlan, APlansPosesAreShownAtThePoseTheirJointsGiveFromHome) {
  const RobotDescription apriori = PaperAprioriRobot();
  PerturbationOptions perturbation;
  perturbation.seed = 1;  // h4cal simulate's defaults
  const SimulatedRobot truth =
      MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel12, perturbation);
  const double plan[24][4] = {
      {-0.15, -0.1, -0.6, 0},   {0.1, -0.1, -0.6, 0},   {0.0, -0.05, -0.6, 60},
      {-0.1, 0.0, -0.6, -60},   {0.0, -0.05, -0.5, 0},  {0.0, -0.05, -0.5, 10},
      {-0.1, 0.05, -0.5, 40},   {0.1, 0.05, -0.5, -40}, {0.0, -0.15, -0.45, 0},
      {0.0, 0.0, -0.45, -60},   {0.05, 0.1, -0.4, 60},  {-0.25, -0.2, -0.3, 40},
      {-0.05, -0.2, -0.3, 60},  {0.25, -0.2, -0.3, 60}, {-0.25, -0.15, -0.3, -60},
      {0.05, -0.15, -0.3, -60}, {-0.25, 0.0, -0.3, 60}, {0.25, 0.0, -0.3, -60},
      {-0.25, 0.15, -0.3, -60}, {-0.2, 0.15, -0.3, 30}, {-0.1, 0.15, -0.3, -60},
      {0.1, 0.15, -0.3, 60},    {0.2, 0.15, -0.3, -30}, {0.25, 0.15, -0.3, 60}};
  SimulatedController controller(truth, apriori.model12, apriori.assembly);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> tick(0.01, 0.3);
  std::vector<int> refused;
  for (int k = 0; k < 24; ++k) {
    const EePose target(plan[k][0], plan[k][1], plan[k][2], RadiansFromDegrees(plan[k][3]));
    const TargetResult result = controller.SetPoseTarget(k + 1, target);
    if (!result.ok()) {
      EXPECT_EQ(result.status, TargetStatus::kUnreachable) << result.reason;
      refused.push_back(k + 1);
      continue;
    }
    for (int step = 0; step < 3000 && !controller.settled(); ++step) controller.Step(tick(rng));
    ASSERT_TRUE(controller.settled()) << "pose " << k + 1;
    SimulatedController from_home(truth, apriori.model12, apriori.assembly);
    ASSERT_TRUE(from_home.SetPoseTarget(k + 1, target).ok());
    for (int step = 0; step < 3000 && !from_home.settled(); ++step) from_home.Step(kDt);
    EXPECT_TRUE(controller.true_X_BE().IsNearlyEqualTo(from_home.true_X_BE(), 1e-9, 1e-9))
        << "pose " << k + 1;
    // The a priori misses by 10-48 mm and up to 25 deg near +-60 deg (the theta gain).
    const double theta = EePoseFromTransform(controller.true_X_BE())[3];
    EXPECT_LT(std::abs(WrapAngle(theta - target[3])), RadiansFromDegrees(30.0)) << "pose " << k + 1;
  }
  EXPECT_EQ(refused, (std::vector<int>{8, 10, 16, 18, 21}));
}

TEST_F(SimulatedControllerTest, UnreachablePoseIsRefusedWithoutMovingAndNeverSettles) {
  ASSERT_TRUE(controller_.SetPoseTarget(1, EePose(0.03, 0.0, -0.45, 0.0)).ok());
  controller_.Step(0.02);  // mid-motion
  const JointVector before = controller_.true_joints();
  const TargetResult result = controller_.SetPoseTarget(2, EePose(0.0, 0.0, -1.5, 0.0));
  EXPECT_EQ(result.status, TargetStatus::kUnreachable);
  EXPECT_NE(result.reason.find("out of reach"), std::string::npos) << result.reason;
  for (int k = 0; k < 100; ++k) controller_.Step(kDt);
  EXPECT_EQ(controller_.true_joints(), before);
  EXPECT_FALSE(controller_.settled());
  EXPECT_TRUE(controller_.refused());
  EXPECT_EQ(controller_.pose_id(), 2);
  // Resending it changes nothing; a reachable target afterwards moves and settles again.
  EXPECT_FALSE(controller_.SetPoseTarget(2, EePose(0.0, 0.0, -1.5, 0.0)).ok());
  EXPECT_FALSE(controller_.settled());
  ASSERT_TRUE(controller_.SetPoseTarget(3, EePose(0.0, 0.0, -0.45, 0.0)).ok());
  EXPECT_FALSE(controller_.refused());
  StepUntilSettled(controller_);
  EXPECT_TRUE(controller_.settled());
  EXPECT_EQ(controller_.pose_id(), 3);
}

TEST_F(SimulatedControllerTest, JointTargetBeyondTheJointRangeIsRefused) {
  JointVector q = controller_.home_joints();
  q[2] = WrapAngle(q[2] + controller_.options().joint_range + 0.01);
  const JointVector before = controller_.true_joints();
  const TargetResult result = controller_.SetJointTarget(6, q);
  EXPECT_EQ(result.status, TargetStatus::kOutsideLimits);
  EXPECT_NE(result.reason.find("joint 3"), std::string::npos) << result.reason;
  controller_.Step(1.0);
  EXPECT_EQ(controller_.true_joints(), before);
  EXPECT_FALSE(controller_.settled());
  EXPECT_EQ(controller_.SetJointTarget(7, JointVector::Constant(std::nan(""))).status,
            TargetStatus::kInvalid);
}

TEST_F(SimulatedControllerTest, RepeatedTargetKeepsTheRobotSettled) {
  const EePose target(0.04, -0.02, -0.43, 0.1);
  ASSERT_TRUE(controller_.SetPoseTarget(9, target).ok());
  StepUntilSettled(controller_);
  ASSERT_TRUE(controller_.settled());
  ASSERT_TRUE(controller_.SetPoseTarget(9, target).ok());
  EXPECT_TRUE(controller_.settled());
  controller_.Step(kDt);
  EXPECT_TRUE(controller_.settled());
  EXPECT_EQ(controller_.pose_id(), 9);
  // A different target does reset it.
  ASSERT_TRUE(controller_.SetPoseTarget(10, EePose(0.04, -0.02, -0.44, 0.1)).ok());
  EXPECT_FALSE(controller_.settled());
}

// The encoder range in the unit and meaning plan and collect take (--joint-range-deg MIN,MAX):
// the controller refuses what the plan was checked against (issue 26 point 9).
TEST_F(SimulatedControllerTest, JointTargetOutsideTheEncoderRangeIsRefusedInDegrees) {
  SimulatedControllerOptions options;
  const JointVector home = controller_.home_joints();
  options.joint_limits = Eigen::Vector2d(home.minCoeff() - 0.1, home.maxCoeff() + 0.1);
  SimulatedController controller(truth_, apriori_.model12, apriori_.assembly, options);
  JointVector q = home;
  EXPECT_TRUE(controller.SetJointTarget(1, q).ok());
  q[1] = home.maxCoeff() + 0.2;
  const TargetResult result = controller.SetJointTarget(2, q);
  EXPECT_EQ(result.status, TargetStatus::kOutsideLimits);
  EXPECT_NE(result.reason.find("joint 2"), std::string::npos) << result.reason;
  EXPECT_NE(result.reason.find(" deg"), std::string::npos) << result.reason;
  options.joint_limits = Eigen::Vector2d(1.0, -1.0);
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
}

TEST_F(SimulatedControllerTest, EncoderNoiseHasTheConfiguredStandardDeviation) {
  SimulatedControllerOptions options;
  options.sigma_q = 3e-4;
  SimulatedController controller(truth_, apriori_.model12, apriori_.assembly, options);
  std::mt19937_64 rng(42);
  constexpr int kDraws = 20000;
  Eigen::Vector4d sum = Eigen::Vector4d::Zero(), sum_sq = Eigen::Vector4d::Zero();
  for (int k = 0; k < kDraws; ++k) {
    const JointVector reading = controller.EncoderReading(rng);
    for (int i = 0; i < 4; ++i) {
      const double e = WrapAngle(reading[i] - controller.true_joints()[i]);
      sum[i] += e;
      sum_sq[i] += e * e;
    }
  }
  for (int i = 0; i < 4; ++i) {
    const double mean = sum[i] / kDraws;
    const double std = std::sqrt(sum_sq[i] / kDraws - mean * mean);
    // Sample std has relative spread 1/sqrt(2N) = 0.5%: 3% is six sigma.
    EXPECT_NEAR(std, options.sigma_q, 0.03 * options.sigma_q) << "joint " << i + 1;
    EXPECT_NEAR(mean, 0.0, 5.0 * options.sigma_q / std::sqrt(kDraws)) << "joint " << i + 1;
  }
}

TEST(SimulatedControllerOptions, RejectsNonPositiveSpeed) {
  SimulatedControllerOptions options;
  options.joint_speed = 0.0;
  EXPECT_TRUE(RefusedNaming(options, "joint speed"));
  EXPECT_THROW(
      SimulatedController(PaperTruthWithPlacement(), kPaperAprioriModel12, Assembly{}, options),
      std::invalid_argument);
}

}  // namespace
}  // namespace h4::host
