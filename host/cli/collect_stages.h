// The two stages of `h4cal collect --sequential FIRST,TOTAL` (issue 29): FIRST poses planned
// on the a priori robot inside the target region, measured; then the rest, up to TOTAL,
// planned on the robot those poses identify (host/planning/sequential_plan.h) and measured
// into the same dataset. Each stage's plan is written beside the dataset, and a resumed
// campaign reads it back instead of planning again, so a restart measures the same poses.
#pragma once

#include <string>
#include <vector>

#include "host/cli/plan_noise_options.h"
#include "host/formats/dataset_csv.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host::cli {

struct CollectStagesOptions {
  int first_count = 0;  ///< poses of the first stage
  int total_count = 0;  ///< poses of both stages
  std::string robot_path, camera_path, board_path;
  std::string joint_range_deg;  ///< "MIN,MAX" or empty, as --joint-range-deg
  std::string dataset_path;     ///< the campaign's --out: the stage files go beside it
  /// What both stages are planned for, as `plan` takes it: the corner noise, and the set-up
  /// spread the first stage must be robust to (the second plans on the identified set-up).
  PlanNoiseOptions noise;
};

/// The free parameters a fit has beside the kinematic ones: the camera's placement X_BC and
/// the board's X_TE, 6 each (parameter_vector.h).
inline constexpr int kPlacementParameterCount = 12;
/// The most poses a sequential campaign may plan: over 12 times the paper's 81 grid poses,
/// within the candidates a default plan has (`20,20000` failed only after the first stage,
/// asking more poses than there are candidates).
inline constexpr int kMaxSequentialPoses = 1000;
/// The fewest poses of a first stage: what identify needs to fit Model 12 at all, a
/// residual per free parameter (kinematic and placement; 6 residuals a pose), and a pose to
/// spare for cross-validation's held-out fold. The first stage's Model 12 fit plans the rest;
/// with fewer (`3,4`) it predicted "inf mm" and a negative chi-square. (identify's verdict
/// calls a fit of fewer than 20 poses too_few_poses: the first stage plans, it does not
/// calibrate.)
int MinimumFirstStagePoses();
/// The fewest poses of the whole campaign: more than the first stage, and a residual per
/// free parameter of Model 31, which the campaign is planned for.
int MinimumSequentialPoses();

/// FIRST,TOTAL of --sequential; throws std::invalid_argument naming the option unless
/// MinimumFirstStagePoses() <= FIRST < TOTAL and MinimumSequentialPoses() <= TOTAL <=
/// kMaxSequentialPoses: checked before anything is planned or moves.
void ParseStageCounts(const std::vector<int>& counts, CollectStagesOptions* options);

/// The stage files beside the dataset DIR/STEM.csv: DIR/STEM.stage1.plan.csv,
/// DIR/STEM.stage2.plan.csv and DIR/STEM.stage1.result.json (the first stage's identification).
struct StageFiles {
  std::string first_plan, second_plan, first_result;
};
StageFiles StageFilesBeside(const std::string& dataset_path);

/// The first stage's poses: read back from StageFiles::first_plan when an earlier run wrote
/// it, else planned on the a priori robot and written there. Says which on stdout.
PosePlan FirstStagePlan(const CollectStagesOptions& options);

/// The second stage's poses: read back when an earlier run wrote them (refused, naming the
/// file and the poses, when empty, reusing a first-stage pose id, or shorter than TOTAL -
/// FIRST: a resumed campaign then never measured the stage), else the rows of the
/// first stage identified (Model 12, then Model 31 from it; the result written to
/// StageFiles::first_result) and TOTAL - rows poses planned on that robot, with pose ids
/// after the first stage's. Throws std::runtime_error when the first stage's rows identify
/// no model, or the plan on it predicts no accuracy (the message says to measure more poses
/// in the first stage); the plan is then not written.
PosePlan SecondStagePlan(const CollectStagesOptions& options, const PosePlan& first_stage,
                         const std::vector<DatasetRow>& first_stage_rows);

}  // namespace h4::host::cli
