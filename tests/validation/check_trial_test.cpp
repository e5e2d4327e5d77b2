// End-to-end trials of `h4cal check` (check_trial.h): simulated grid campaigns identified
// as `h4cal identify` does, the result through its JSON text, then 5 check poses on the
// unchanged robot and on the robot after a 3-sigma joint offset drift. A few seeded trials
// here (at most one wrong verdict each way in 10); the full rate over many trials is
// h4_check_study's (docs/results.md#checking-for-drift-h4cal-check).
#include "host/validation/check_trial.h"

#include <gtest/gtest.h>

#include "host/kinematics/paper_robot.h"

namespace h4::host {
namespace {

constexpr int kCheckTrials = 10;

CheckTrialOptions FastTrialOptions() {
  CheckTrialOptions options;
  options.calibration_plan = GridPosePlan();
  const PosePlan& grid = options.calibration_plan;
  options.check_plan = {grid[4], grid[22], grid[40], grid[58], grid[76]};
  options.identification.cross_validation.folds = 0;  // the covariance does not need it
  return options;
}

struct Tally {
  int trials = 0, unchanged_flagged = 0, drifted_flagged = 0;
};

Tally RunTrials(const CheckTrialOptions& options) {
  const RobotDescription apriori = PaperAprioriRobot();
  Tally tally;
  for (int trial = 1; trial <= kCheckTrials; ++trial) {
    const SimulatedRobot truth = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31,
                                               {.seed = static_cast<uint64_t>(1 + trial % 5)});
    const CheckTrialOutcome outcome =
        RunCheckTrial(apriori, truth, static_cast<uint64_t>(trial), options);
    EXPECT_TRUE(outcome.identified) << "trial " << trial << ": " << outcome.message;
    if (options.drift_sigmas > 0.0) {
      EXPECT_GT(std::abs(outcome.joint_offset_change), 0.0);
    }
    tally.trials += outcome.identified ? 1 : 0;
    tally.unchanged_flagged += outcome.unchanged.drift ? 1 : 0;
    tally.drifted_flagged += outcome.drifted.drift ? 1 : 0;
  }
  return tally;
}

// Every trial identified; at most one wrong verdict each way.
void ExpectRightVerdicts(const Tally& tally) {
  EXPECT_EQ(tally.trials, kCheckTrials);
  EXPECT_LE(tally.unchanged_flagged, 1);
  EXPECT_GE(tally.drifted_flagged, kCheckTrials - 1);
}

TEST(CheckTrial, IdentifiedResultsPassTheUnchangedRobotAndFlagA3SigmaDrift) {
  ExpectRightVerdicts(RunTrials(FastTrialOptions()));
}

// The same trials with a drift of 0 sigma: the "drifted" robot is the unchanged one and is
// flagged no more often (the test can tell a drift from none).
TEST(CheckTrial, A0SigmaDriftIsNotFlagged) {
  CheckTrialOptions options = FastTrialOptions();
  options.drift_sigmas = 0.0;
  const Tally tally = RunTrials(options);
  EXPECT_LE(tally.drifted_flagged, 1);
}

// A camera whose stated pose covariance is optimistic, as the live demo's rendered camera's
// is (its covariance holds the corner noise alone): the rows state a quarter of the rotation
// noise and half the translation noise. The calibration's residuals show it; the check
// allows for it (the result's camera_error_floor) and still flags a 3-sigma drift.
CheckTrialOptions OptimisticCameraOptions() {
  CheckTrialOptions options = FastTrialOptions();
  options.stated_noise =
      NoiseOptions{options.noise.sigma_t / 2.0, options.noise.sigma_r / 4.0, options.noise.sigma_q};
  return options;
}

TEST(CheckTrial, AnOptimisticCameraCovarianceIsAllowedForAndADriftStillFlagged) {
  ExpectRightVerdicts(RunTrials(OptimisticCameraOptions()));
}

// Judged by the stated covariance alone (what `h4cal check` did before the floor), the same
// unchanged robots are flagged most of the time: the trials above can tell the difference.
TEST(CheckTrial, TheStatedOptimisticCovarianceAloneCriesDrift) {
  CheckTrialOptions options = OptimisticCameraOptions();
  options.stated_camera_covariance = true;
  options.drift_sigmas = 0.0;
  const Tally tally = RunTrials(options);
  EXPECT_GE(tally.unchanged_flagged, kCheckTrials / 2);
}

TEST(CheckTrial, InvalidOptionsAreRefused) {
  CheckTrialOptions options = FastTrialOptions();
  options.check_plan.clear();
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("check_plan"), std::string::npos);
  EXPECT_THROW(RunCheckTrial(PaperAprioriRobot(),
                             MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31), 1,
                             options),
               std::invalid_argument);
}

}  // namespace
}  // namespace h4::host
