// The check study (`h4cal check`, host/validation/check_trial.h): over simulated Model 31
// robots and noise seeds, how often the check is right end to end. Each trial simulates
// the paper's 81-pose grid on the robot (the noise of `h4cal simulate`), identifies it as
// `h4cal identify` does (Model 12, then Model 31 from it, every default), reads the result
// back from its JSON text, then simulates a 5-pose verification campaign on the unchanged
// robot and on the robot after one joint offset moved by `--drift-sigmas` of the result's
// predicted error (RMS Mahalanobis over the check poses), and counts the verdicts.
//
//   h4_check_study [--robots R] [--seeds S] [--drift-sigmas 3] [--check-poses grid|planned]
//                  [--without-covariance 1] [--stated-sigma-fraction R,T]
//                  [--stated-camera-covariance 1] [--source-dir DIR]
// --without-covariance 1: check as against results written before parameter_covariance
// (their sigmas alone); the drift is still sized with the full covariance.
// --stated-sigma-fraction R,T: the camera states R times the rotation noise and T times the
// translation noise (an optimistic pose covariance, as the rendered camera's); with
// --stated-camera-covariance 1 the check ignores the result's camera_error_floor (as
// `h4cal check --stated-camera-covariance`).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <fmt/core.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/timing/clock.h"
#include "host/bench/study_main.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/pose_planner.h"
#include "host/validation/check_trial.h"

namespace h4::host {
namespace {

struct StudyOptions {
  int robots = 5;
  int seeds = 20;
  double drift_sigmas = 3.0;
  bool planned_check_poses = false;  ///< 5 poses from the planner (else 5 grid poses)
  bool without_covariance = false;   ///< results as before parameter_covariance (sigmas)
  double stated_fraction_r = 1.0, stated_fraction_t = 1.0;  ///< stated sigma / true noise
  bool stated_camera_covariance = false;  ///< check without the camera_error_floor
  std::string source_dir = H4_SOURCE_DIR;
};

StudyOptions ParseOptions(int argc, char** argv) {
  StudyOptions options;
  ForEachFlagAndValue(argc, argv, [&options](const std::string& flag, const std::string& value) {
    if (flag == "--robots") {
      options.robots = std::stoi(value);
    } else if (flag == "--seeds") {
      options.seeds = std::stoi(value);
    } else if (flag == "--drift-sigmas") {
      options.drift_sigmas = std::stod(value);
    } else if (flag == "--check-poses") {
      if (value != "grid" && value != "planned")
        throw std::invalid_argument("--check-poses grid|planned");
      options.planned_check_poses = value == "planned";
    } else if (flag == "--without-covariance") {  // VALUE: 1 or 0
      options.without_covariance = value == "1";
    } else if (flag == "--stated-sigma-fraction") {  // R,T
      const size_t comma = value.find(',');
      if (comma == std::string::npos) throw std::invalid_argument("--stated-sigma-fraction R,T");
      options.stated_fraction_r = std::stod(value.substr(0, comma));
      options.stated_fraction_t = std::stod(value.substr(comma + 1));
    } else if (flag == "--stated-camera-covariance") {  // VALUE: 1 or 0
      options.stated_camera_covariance = value == "1";
    } else if (flag == "--source-dir") {
      options.source_dir = value;
    } else {
      throw std::invalid_argument("unknown option " + flag);
    }
  });
  return options;
}

// 5 planned poses (D-optimal: the most informative about the parameters a drift moves).
PosePlan PlannedCheckPoses(const std::string& source_dir) {
  const PlanningProblem problem = MakePlanningProblem(
      PaperAprioriRobot(),
      CameraModel(ReadCameraYaml(source_dir + "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(source_dir + "/boards/aprilgrid_6x6_30mm.yaml")),
      PlanningProblemOptions{});
  DesignOptions design;
  design.pose_count = 5;
  return PlanCampaign(problem, design, 1001, PlanCriterion::kDOptimal).plan;
}

PosePlan GridCheckPoses() {
  const PosePlan grid = GridPosePlan();
  return {grid[4], grid[22], grid[40], grid[58], grid[76]};
}

// What the trials came to.
struct Tally {
  int trials = 0;  ///< identified campaigns, each checked unchanged and drifted
  int unusable = 0;
  int unchanged_passed = 0;
  int drifted_flagged = 0;
};

void PrintTrial(int robot, int seed, const CheckTrialOutcome& outcome) {
  fmt::print(
      "robot {} seed {}: joint {} offset {:+.4f} mrad; unchanged chi2 {:.1f} {}, drifted chi2 "
      "{:.1f} {} ({} dof)\n",
      robot, seed, outcome.drifted_joint + 1, outcome.joint_offset_change * 1e3,
      outcome.unchanged.chi2, outcome.unchanged.drift ? "FLAGGED" : "passed", outcome.drifted.chi2,
      outcome.drifted.drift ? "flagged" : "MISSED", outcome.unchanged.dof);
  std::fflush(stdout);
}

void PrintTally(const StudyOptions& study, const Tally& tally, double seconds) {
  fmt::print("\n| trials | unchanged robot passed | {:.3g}-sigma drift flagged |\n",
             study.drift_sigmas);
  fmt::print("|---|---|---|\n");
  fmt::print("| {} | {} ({:.1f} %) | {} ({:.1f} %) |\n", tally.trials, tally.unchanged_passed,
             100.0 * tally.unchanged_passed / std::max(tally.trials, 1), tally.drifted_flagged,
             100.0 * tally.drifted_flagged / std::max(tally.trials, 1));
  fmt::print(
      "{} unusable identifications; {} robots x {} seeds, {} check poses; stated sigmas {:.3g} x "
      "the rotation noise, {:.3g} x the translation noise, checked {}; {:.0f} s\n",
      tally.unusable, study.robots, study.seeds, study.planned_check_poses ? "planned" : "grid",
      study.stated_fraction_r, study.stated_fraction_t,
      study.stated_camera_covariance ? "against the stated covariance alone"
                                     : "with the result's camera_error_floor",
      seconds);
}

void Run(const StudyOptions& study) {
  const auto start = std::chrono::steady_clock::now();
  const RobotDescription apriori = PaperAprioriRobot();
  CheckTrialOptions options;
  options.calibration_plan = GridPosePlan();
  options.check_plan =
      study.planned_check_poses ? PlannedCheckPoses(study.source_dir) : GridCheckPoses();
  options.drift_sigmas = study.drift_sigmas;
  options.without_covariance = study.without_covariance;
  if (study.stated_fraction_r != 1.0 || study.stated_fraction_t != 1.0) {
    options.stated_noise =
        NoiseOptions{options.noise.sigma_t * study.stated_fraction_t,
                     options.noise.sigma_r * study.stated_fraction_r, options.noise.sigma_q};
  }
  options.stated_camera_covariance = study.stated_camera_covariance;
  Tally tally;
  for (int robot = 1; robot <= study.robots; ++robot) {
    const SimulatedRobot truth = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31,
                                               {.seed = static_cast<uint64_t>(robot)});
    for (int seed = 1; seed <= study.seeds; ++seed) {
      // One seed per trial: the calibration noise, the check noise and the drifted joint
      // differ between robots too.
      const auto trial_seed = static_cast<uint64_t>((robot - 1) * study.seeds + seed);
      const CheckTrialOutcome outcome = RunCheckTrial(apriori, truth, trial_seed, options);
      if (!outcome.identified) {
        ++tally.unusable;
        fmt::print("robot {} seed {}: {}\n", robot, seed, outcome.message);
        continue;
      }
      ++tally.trials;
      tally.unchanged_passed += outcome.unchanged.drift ? 0 : 1;
      tally.drifted_flagged += outcome.drifted.drift ? 1 : 0;
      PrintTrial(robot, seed, outcome);
    }
  }
  PrintTally(study, tally, SecondsSince(start));
}

}  // namespace
}  // namespace h4::host

int main(int argc, char** argv) {
  return h4::host::StudyMain("h4_check_study", argc, argv, h4::host::ParseOptions, h4::host::Run);
}
