// The stages of a sequential campaign, planned for `h4cal collect` (collect_stages.h).
#include "host/cli/collect_stages.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/cli/calibration_workflow.h"
#include "host/cli/identification_print.h"
#include "host/cli/plan_reach.h"
#include "host/formats/identification_result.h"
#include "host/formats/pose_plan_rows.h"
#include "host/formats/poses_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/identification/identification.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/planning/pose_planner.h"
#include "host/planning/sequential_plan.h"

namespace h4::host::cli {
namespace {

namespace fs = std::filesystem;

/// `plan`'s defaults (the target region is the paper's grid box; robots drawn from the a
/// priori uncertainty) with the campaign's joint range and measurement noise.
PlanningProblemOptions StageProblemOptions(const CollectStagesOptions& options) {
  PlanningProblemOptions problem;
  problem.candidates.joint_range = ParseJointRange(options.joint_range_deg);
  ApplyPlanNoise(options.noise, &problem);
  return problem;
}

PlannedCampaign PlanStage(const CollectStagesOptions& options, const RobotDescription& robot,
                          const PlanningProblemOptions& problem_options, int count,
                          int64_t first_id) {
  const CameraModel camera(ReadCameraYaml(options.camera_path));
  const BoardModel board(ReadBoardYaml(options.board_path));
  const PlanningProblem problem = MakePlanningProblem(robot, camera, board, problem_options);
  DesignOptions design;
  design.pose_count = count;
  const PlannedCampaign planned = PlanCampaign(problem, design, first_id, PlanCriterion::kAccuracy);
  if (planned.plan.empty()) {
    throw std::runtime_error(fmt::format("{}: no candidate pose to plan ({})", options.robot_path,
                                         problem.candidates.Summary()));
  }
  return planned;
}

/// The plan an earlier run of the same campaign wrote, if any (its poses, not planned again).
/// An empty one is refused: a campaign over it measured nothing and exited 0.
std::optional<PosePlan> ReadEarlierPlan(const std::string& path, const char* stage) {
  if (!fs::exists(path)) return std::nullopt;
  PosePlan plan = PosePlanFromRows(ReadPosesCsv(path));
  if (plan.empty()) {
    throw std::runtime_error(fmt::format(
        "{}: {} plan written by an earlier run holds no pose (damaged?): nothing measured; "
        "remove it to plan the stage again",
        path, stage));
  }
  fmt::print("{}: {} poses, planned by an earlier run ({})\n", stage, plan.size(), path);
  return plan;
}

/// A second stage's plan read back must be the rest of the campaign: none of its pose ids
/// in the first stage (a resumed campaign then counted those as measured and never measured
/// stage 2, exit 0), and at least TOTAL - FIRST poses. Throws std::runtime_error naming the
/// file and the poses otherwise.
void CheckEarlierSecondStage(const CollectStagesOptions& options, const std::string& path,
                             const PosePlan& first_stage, const PosePlan& second_stage) {
  std::set<int64_t> first_ids;
  for (const PlannedPose& pose : first_stage) first_ids.insert(pose.pose_id);
  std::vector<int64_t> reused;
  for (const PlannedPose& pose : second_stage) {
    if (first_ids.count(pose.pose_id)) reused.push_back(pose.pose_id);
  }
  if (!reused.empty()) {
    throw std::runtime_error(fmt::format(
        "{}: the stage 2 of 2 plan reuses pose ids of the first stage ({}): its poses would "
        "never be measured; remove it to plan the stage again",
        path, fmt::join(reused, ", ")));
  }
  const size_t needed =
      static_cast<size_t>(std::max(1, options.total_count - static_cast<int>(first_stage.size())));
  if (second_stage.size() < needed) {
    throw std::runtime_error(fmt::format(
        "{}: the stage 2 of 2 plan holds {} poses, the campaign of {} after the first stage's "
        "{} needs at least {} (damaged, or another TOTAL): remove it to plan the stage again",
        path, second_stage.size(), options.total_count, first_stage.size(), needed));
  }
}

/// "1.70 mm", or what stands in for a figure that is not there.
std::string FormatRmsMm(double rms_m) {
  if (std::isinf(rms_m)) return "not usable";
  if (rms_m == std::numeric_limits<double>::max()) return "not measured";
  return fmt::format("{:.2f} mm", rms_m * 1e3);
}

/// How well an outcome predicts poses it was not fitted to: its cross-validated (else
/// held-out) board position RMS, m; infinity when it is not usable, the largest double when
/// it has neither figure.
double HeldOutPositionRms(const IdentificationOutcome& outcome) {
  if (!outcome.summary.usable) return std::numeric_limits<double>::infinity();
  const IdentificationResult& result = outcome.result;
  if (result.cross_validation) return result.cross_validation->position_rms_m;
  return result.valid_position_rms_m.value_or(std::numeric_limits<double>::max());
}

/// Model 12, then Model 31 from it, as `collect --report-dir` does; the result that predicts
/// the poses it was not fitted to best, Model 31 on a tie. With the few poses of a first
/// stage, Model 31 can fit them and predict nothing: in one live run of 8 poses it held
/// one out as an outlier and predicted the rest to 171 mm and 93 deg, Model 12 to 1.7 mm,
/// and a second stage planned on Model 31's camera found no candidate it would see.
IdentificationResult IdentifyFirstStage(const RobotDescription& apriori,
                                        const std::vector<DatasetRow>& rows,
                                        const std::string& result_path,
                                        const std::vector<std::string>& inputs) {
  const auto [m12, m31] = IdentifyModel12Then31(apriori, rows, IdentificationOptions{});
  PrintHeadline(m12);
  PrintHeadline(m31);
  const double rms12 = HeldOutPositionRms(m12);
  const double rms31 = HeldOutPositionRms(m31);
  if (std::isinf(rms12) && std::isinf(rms31)) {
    throw std::runtime_error(fmt::format(
        "the first stage's {} poses identify neither model ({}): measure more poses in the "
        "first stage (--sequential FIRST,TOTAL with a larger FIRST)",
        rows.size(), m31.summary.message));
  }
  const IdentificationOutcome& kept = rms31 <= rms12 ? m31 : m12;
  fmt::print(
      "stage 1 of 2: the rest is planned on the Model {} result (held-out board "
      "position RMS: Model 12 {}, Model 31 {})\n",
      ToString(kept.result.model), FormatRmsMm(rms12), FormatRmsMm(rms31));
  WriteResultWithProvenance(result_path, kept.result, inputs);
  return kept.result;
}

}  // namespace

namespace {

/// Poses of 6 residuals each to have at least one residual per parameter.
int PosesForParameters(int parameters) { return (parameters + 5) / 6; }

}  // namespace

int MinimumFirstStagePoses() {
  return PosesForParameters(Model12::kParameterCount + kPlacementParameterCount) + 1;
}

int MinimumSequentialPoses() {
  return std::max(MinimumFirstStagePoses() + 1,
                  PosesForParameters(Model31::kParameterCount + kPlacementParameterCount));
}

void ParseStageCounts(const std::vector<int>& counts, CollectStagesOptions* options) {
  const int first_min = MinimumFirstStagePoses();
  const int total_min = MinimumSequentialPoses();
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(fmt::format(
        "--sequential FIRST,TOTAL: {}; FIRST poses in the first stage, at least {} (a "
        "residual per free parameter of Model 12, which the rest is planned on, and a pose to "
        "spare), TOTAL in the campaign, FIRST < TOTAL, {}..{} (e.g. 20,71)",
        what, first_min, total_min, kMaxSequentialPoses));
  };
  if (counts.size() != 2) fail("expected two numbers");
  if (counts[0] < first_min) fail(fmt::format("FIRST {} is too few", counts[0]));
  if (counts[0] >= counts[1]) fail(fmt::format("FIRST {} >= TOTAL {}", counts[0], counts[1]));
  if (counts[1] < total_min || counts[1] > kMaxSequentialPoses) {
    fail(fmt::format("TOTAL {} is out of range", counts[1]));
  }
  options->first_count = counts[0];
  options->total_count = counts[1];
}

StageFiles StageFilesBeside(const std::string& dataset_path) {
  const fs::path dataset(dataset_path);
  const fs::path stem = dataset.parent_path() / dataset.stem();
  return {stem.string() + ".stage1.plan.csv", stem.string() + ".stage2.plan.csv",
          stem.string() + ".stage1.result.json"};
}

PosePlan FirstStagePlan(const CollectStagesOptions& options) {
  const StageFiles files = StageFilesBeside(options.dataset_path);
  if (std::optional<PosePlan> earlier = ReadEarlierPlan(files.first_plan, "stage 1 of 2")) {
    return *earlier;
  }
  const RobotDescription apriori = ReadRobotYaml(options.robot_path);
  const PlannedCampaign planned = PlanStage(
      options, apriori, FirstStageOptions(StageProblemOptions(options)), options.first_count, 1);
  WritePosesCsv(files.first_plan, RowsFromPosePlan(planned.plan));
  // Fewer poses than Model 31's free parameters predict no accuracy alone: said in words.
  const std::string predicted =
      std::isfinite(planned.predicted_position_rms)
          ? fmt::format("predicted {:.4f} mm alone", planned.predicted_position_rms * 1e3)
          : "too few to predict an accuracy alone";
  fmt::print(
      "stage 1 of 2: {} poses planned on the a priori robot inside the target region ({}), "
      "written to {}\n",
      planned.plan.size(), predicted, files.first_plan);
  return planned.plan;
}

PosePlan SecondStagePlan(const CollectStagesOptions& options, const PosePlan& first_stage,
                         const std::vector<DatasetRow>& first_stage_rows) {
  const StageFiles files = StageFilesBeside(options.dataset_path);
  if (std::optional<PosePlan> earlier = ReadEarlierPlan(files.second_plan, "stage 2 of 2")) {
    CheckEarlierSecondStage(options, files.second_plan, first_stage, *earlier);
    return *earlier;
  }
  fmt::print("stage 1 of 2 measured: identifying its {} poses to plan the rest on\n",
             first_stage_rows.size());
  const RobotDescription apriori = ReadRobotYaml(options.robot_path);
  const IdentificationResult first =
      IdentifyFirstStage(apriori, first_stage_rows, files.first_result,
                         {options.robot_path, options.dataset_path});
  const RobotDescription identified = IdentifiedDescription(apriori, first);
  int64_t last_id = 0;
  for (const PlannedPose& pose : first_stage) last_id = std::max(last_id, pose.pose_id);
  for (const DatasetRow& row : first_stage_rows) last_id = std::max(last_id, row.pose_id);
  const int count = std::max(1, options.total_count - static_cast<int>(first_stage_rows.size()));
  const PlannedCampaign planned =
      PlanStage(options, identified,
                NextStageOptions(StageProblemOptions(options), identified, first_stage_rows), count,
                last_id + 1);
  if (!std::isfinite(planned.predicted_position_rms)) {
    throw std::runtime_error(fmt::format(
        "stage 2 of 2: the {} poses planned with the {} measured predict no accuracy (the "
        "robot stage 1 identified, {}, cannot be trusted to plan on): nothing measured; "
        "measure more poses in the first stage (--sequential FIRST,TOTAL with a larger FIRST)",
        planned.plan.size(), first_stage_rows.size(), files.first_result));
  }
  WritePosesCsv(files.second_plan, RowsFromPosePlan(planned.plan));
  fmt::print(
      "stage 2 of 2: {} poses planned on the robot stage 1 identified ({}), predicted {:.4f} mm "
      "with the {} measured, written to {}\n",
      planned.plan.size(), files.first_result, planned.predicted_position_rms * 1e3,
      first_stage_rows.size(), files.second_plan);
  return planned.plan;
}

}  // namespace h4::host::cli
