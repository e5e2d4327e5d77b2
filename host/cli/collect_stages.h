// The two stages of `h4cal collect --sequential FIRST,TOTAL` (issue 29): FIRST poses planned
// on the a priori robot inside the target region, measured; then the rest, up to TOTAL,
// planned on the robot those poses identify (host/planning/sequential_plan.h) and measured
// into the same dataset. Each stage's plan is written beside the dataset, and a resumed
// campaign reads it back instead of planning again, so a restart measures the same poses.
#pragma once

#include <string>
#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host::cli {

struct CollectStagesOptions {
  int first_count = 0;  ///< poses of the first stage
  int total_count = 0;  ///< poses of both stages
  std::string robot_path, camera_path, board_path;
  std::string joint_range_deg;  ///< "MIN,MAX" or empty, as --joint-range-deg
  std::string dataset_path;     ///< the campaign's --out: the stage files go beside it
};

/// FIRST,TOTAL of --sequential; throws std::invalid_argument naming the option unless
/// 0 < FIRST < TOTAL.
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

/// The second stage's poses: read back when an earlier run wrote them, else the rows of the
/// first stage identified (Model 12, then Model 31 from it; the result written to
/// StageFiles::first_result) and TOTAL - rows poses planned on that robot, with pose ids
/// after the first stage's. Throws std::runtime_error when the first stage's rows identify
/// no model (the message says to measure more poses in the first stage).
PosePlan SecondStagePlan(const CollectStagesOptions& options, const PosePlan& first_stage,
                         const std::vector<DatasetRow>& first_stage_rows);

}  // namespace h4::host::cli
