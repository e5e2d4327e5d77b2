// Tests of the simulated controller on real LCM traffic (the in-process memq:// provider):
// joint states and board truths at the rate, a target published on the bus reached and
// settled under its pose id, refused targets (answered with the reason on H4_TARGET_STATUS),
// and garbage counted rather than fatal.
#include "host/campaign/sim_robot_node.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <h4msgs/target_status_t.hpp>

#include "common/geometry/rotation.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "messages/channels.h"
#include "tests/campaign/joint_test_helpers.h"

namespace h4::host {
namespace {

using Seconds = std::chrono::duration<double>;

class SimRobotNodeTest : public ::testing::Test {
 protected:
  SimRobotNodeTest()
      : bus_("memq://"),
        apriori_(PaperAprioriRobot()),
        truth_(MakeTrueRobot(apriori_, TrueGeometry::kPaperTable2)),
        controller_(truth_, apriori_.model12, apriori_.assembly),
        node_(bus_, controller_, NodeOptions()) {
    bus_.Subscribe<h4msgs::joint_state_t>(
        channels::kJointState, [this](const h4msgs::joint_state_t& m) { states_.push_back(m); });
    bus_.Subscribe<h4msgs::sim_board_truth_t>(
        channels::kSimBoardTruth,
        [this](const h4msgs::sim_board_truth_t& m) { truths_.push_back(m); });
    bus_.Subscribe<h4msgs::target_status_t>(
        channels::kTargetStatus,
        [this](const h4msgs::target_status_t& m) { answers_.push_back(m); });
  }
  static SimRobotNodeOptions NodeOptions() {
    SimRobotNodeOptions options;
    options.status_period_s = 0.0;
    return options;
  }
  void SetUp() override { ASSERT_TRUE(bus_.good()); }

  void PublishPoseTarget(int64_t pose_id, const EePose& x) {
    h4msgs::robot_target_t target{};
    target.pose_id = pose_id;
    target.target_type = h4msgs::robot_target_t::TARGET_POSE;
    for (int k = 0; k < 4; ++k) target.pose[k] = x[k];
    ASSERT_TRUE(bus_.Publish(channels::kRobotTarget, target));
  }
  // The node publishes into the same memq queue; drain what it sent last.
  void Drain() { bus_.Handle(std::chrono::milliseconds(0)); }

  bus::LcmBus bus_;
  RobotDescription apriori_;
  SimulatedRobot truth_;
  SimulatedController controller_;
  SimRobotNode node_;
  std::vector<h4msgs::joint_state_t> states_;
  std::vector<h4msgs::sim_board_truth_t> truths_;
  std::vector<h4msgs::target_status_t> answers_;
};

// The rate itself is PeriodicSchedule's, tested on synthetic times (periodic_schedule_test):
// here only what holds however loaded the machine is.
TEST_F(SimRobotNodeTest, PublishesSettledHomeStatesFromTheStartNeverAboveTheRate) {
  const int64_t before_us = std::chrono::duration_cast<std::chrono::microseconds>(
                                std::chrono::system_clock::now().time_since_epoch())
                                .count();
  node_.RunFor(Seconds(1.0));
  Drain();
  // One state at the start, then one per 10 ms slot before the end: at most 100 in 1 s
  // (a loaded machine misses slots, never adds any).
  EXPECT_GE(states_.size(), 1u);
  EXPECT_LE(states_.size(), 100u);
  EXPECT_EQ(truths_.size(), states_.size());
  EXPECT_EQ(node_.joint_states_published(), static_cast<int64_t>(states_.size()));
  for (const auto& state : states_) {
    EXPECT_EQ(state.pose_id, -1);
    EXPECT_TRUE(state.settled);
    ASSERT_EQ(state.joint_count, 4);
    ASSERT_EQ(state.position.size(), 4u);
    EXPECT_GE(state.utime, before_us);
  }
  for (size_t k = 1; k < states_.size(); ++k) EXPECT_GT(states_[k].utime, states_[k - 1].utime);
}

TEST_F(SimRobotNodeTest, PoseTargetOnTheBusIsReachedAndSettledUnderItsPoseId) {
  const EePose target(0.02, -0.01, -0.45, 0.05);
  const int64_t published_us = std::chrono::duration_cast<std::chrono::microseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count();
  PublishPoseTarget(12, target);
  // Until settled under id 12 (about 0.5 s of motion and dwell), however slow the machine.
  for (int k = 0; k < 600 && !(controller_.settled() && controller_.pose_id() == 12); ++k) {
    node_.RunFor(Seconds(0.05));
  }
  Drain();
  ASSERT_FALSE(states_.empty());
  EXPECT_EQ(node_.targets_received(), 1);
  // The first state may precede the target (published at start, settled at home, id -1);
  // then moving under pose id 12, not settled, and settled from some point on.
  size_t first_moving = states_.size(), first_settled = states_.size();
  for (size_t k = 0; k < states_.size(); ++k) {
    if (states_[k].pose_id != 12) {
      EXPECT_EQ(k, 0u);
      EXPECT_EQ(states_[k].pose_id, -1);
      continue;
    }
    if (!states_[k].settled && first_moving == states_.size()) first_moving = k;
    if (states_[k].settled && first_settled == states_.size()) first_settled = k;
    if (first_settled < k) {
      EXPECT_TRUE(states_[k].settled) << "state " << k;
    }
  }
  ASSERT_LT(first_settled, states_.size());
  EXPECT_LT(first_moving, first_settled);
  // The controller runs on the clock: settled no sooner than the move plus settle_time
  // after the target was sent, however few states a loaded machine published in between.
  EXPECT_GE(states_[first_settled].utime - published_us,
            static_cast<int64_t>(controller_.options().settle_time * 1e6));
  EXPECT_TRUE(states_.back().settled);
  EXPECT_EQ(states_.back().pose_id, 12);

  // At rest at the a priori IK joints; the readings scatter about them by sigma_q.
  const IkResult ik = Model12(apriori_.model12, apriori_.assembly).InverseKinematics(target);
  ASSERT_TRUE(ik.ok());
  const double sigma_q = controller_.options().sigma_q;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(WrapAngle(controller_.true_joints()[i] - ik.q[i]), 0.0, 1e-12);
    EXPECT_NEAR(WrapAngle(states_.back().position[static_cast<size_t>(i)] - ik.q[i]), 0.0,
                6.0 * sigma_q);
  }
  // The truth messages carry the controller's true board pose, a unit quaternion.
  const h4msgs::sim_board_truth_t& last = truths_.back();
  EXPECT_EQ(last.pose_id, 12);
  EXPECT_TRUE(last.settled);
  const RigidTransform X_CT = RigidTransform::FromTranslationQuaternion(
      Eigen::Vector3d(last.translation[0], last.translation[1], last.translation[2]),
      Eigen::Vector4d(last.quaternion[0], last.quaternion[1], last.quaternion[2],
                      last.quaternion[3]));
  EXPECT_NEAR(Eigen::Vector4d(last.quaternion[0], last.quaternion[1], last.quaternion[2],
                              last.quaternion[3])
                  .norm(),
              1.0, 1e-12);
  EXPECT_TRUE(X_CT.IsNearlyEqualTo(controller_.true_X_CT(), 1e-12, 1e-12));
  // While moving, the board moved too: the first truth is not the settled one.
  const auto& first = truths_[first_moving];
  const Eigen::Vector3d p_first(first.translation[0], first.translation[1], first.translation[2]);
  EXPECT_GT((p_first - X_CT.translation()).norm(), 1e-4);
}

TEST_F(SimRobotNodeTest, UnreachableTargetIsHeldUnsettledUnderItsPoseId) {
  PublishPoseTarget(20, EePose(0.0, 0.0, -1.5, 0.0));
  node_.RunFor(Seconds(0.4));
  Drain();
  EXPECT_EQ(node_.targets_refused(), 1);
  ASSERT_FALSE(states_.empty());
  // After the start-up state (id -1, before the target arrived): id 20, never settled.
  for (size_t k = 1; k < states_.size(); ++k) {
    EXPECT_EQ(states_[k].pose_id, 20);
    EXPECT_FALSE(states_[k].settled);
  }
  EXPECT_EQ(states_.back().pose_id, 20);
  EXPECT_LT(MaxWrappedJointDifference(controller_.true_joints(), controller_.home_joints()), 1e-15);
}

// The campaign learns of a refusal at once, with the controller's reason, instead of
// waiting out its settle timeout; an accepted target is answered too.
TEST_F(SimRobotNodeTest, EveryTargetIsAnsweredAndARefusalCarriesItsReason) {
  PublishPoseTarget(20, EePose(0.0, 0.0, -1.5, 0.0));
  node_.RunFor(Seconds(0.1));
  PublishPoseTarget(21, EePose(0.02, -0.01, -0.45, 0.05));
  node_.RunFor(Seconds(0.1));
  Drain();
  // Copies of lcm-gen's constants: EXPECT_EQ binds a reference, and they have no definition.
  const int8_t unreachable = h4msgs::target_status_t::STATUS_UNREACHABLE;
  const int8_t accepted = h4msgs::target_status_t::STATUS_ACCEPTED;
  ASSERT_EQ(answers_.size(), 2u);
  EXPECT_EQ(answers_[0].pose_id, 20);
  EXPECT_EQ(answers_[0].status, unreachable);
  EXPECT_NE(answers_[0].reason.find("out of reach of the a priori model"), std::string::npos)
      << answers_[0].reason;
  EXPECT_GT(answers_[0].utime, 0);
  EXPECT_EQ(answers_[1].pose_id, 21);
  EXPECT_EQ(answers_[1].status, accepted);
  EXPECT_EQ(answers_[1].reason, "");
}

TEST_F(SimRobotNodeTest, GarbageOnTheTargetChannelIsCountedNotFatal) {
  const unsigned char garbage[5] = {1, 2, 3, 4, 5};
  ASSERT_EQ(bus_.lcm().publish(channels::kRobotTarget, garbage, sizeof(garbage)), 0);
  node_.RunFor(Seconds(0.2));
  Drain();
  EXPECT_EQ(bus_.decode_failures(), 1);
  EXPECT_EQ(node_.targets_received(), 0);
  ASSERT_FALSE(states_.empty());
  EXPECT_TRUE(states_.back().settled);
  EXPECT_EQ(states_.back().pose_id, -1);
}

TEST_F(SimRobotNodeTest, RunReturnsPromptlyWhenTheStopFlagIsSet) {
  std::atomic<bool> stop{false};
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop.store(true);
  });
  const auto start = std::chrono::steady_clock::now();
  node_.Run(stop);
  const double elapsed = Seconds(std::chrono::steady_clock::now() - start).count();
  stopper.join();
  // Returned after the flag was set, and (the loop waits at most 100 ms on the bus) not
  // only at some later event: a node that missed the flag would run until ctest's timeout.
  EXPECT_GE(elapsed, 0.19);
  EXPECT_LT(elapsed, 30.0);
  EXPECT_GT(node_.joint_states_published(), 0);
}

}  // namespace
}  // namespace h4::host
