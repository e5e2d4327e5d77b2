// Pose planning end to end (pose_planner.h).
#include "host/planning/pose_planner.h"

#include <algorithm>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "host/identification/verdict.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

// The grid poses the a priori robot reaches, by the rule the information model applies
// (SimulateDataset's inverse kinematics); the others' ids go to *unreachable.
PosePlan ReachableGridPoses(const RobotDescription& robot, std::vector<int64_t>* unreachable) {
  const PosePlan grid = GridPosePlan();
  DatasetOptions options;
  options.noise = NoiseOptions{0.0, 0.0, 0.0};
  options.valid_count = 0;
  *unreachable = SimulateDataset(SimulatedRobot::FromDescription(robot), grid, options).unreachable;
  PosePlan reachable;
  for (const PlannedPose& pose : grid) {
    if (std::find(unreachable->begin(), unreachable->end(), pose.pose_id) == unreachable->end()) {
      reachable.push_back(pose);
    }
  }
  return reachable;
}

}  // namespace

PlanningProblem MakePlanningProblem(const RobotDescription& robot, const CameraModel& camera,
                                    const BoardModel& board,
                                    const PlanningProblemOptions& options) {
  PlanningProblem problem;
  problem.candidates = MakeCandidateSet(robot, camera, board, options.candidates);
  if (problem.candidates.poses.empty()) {
    throw std::invalid_argument("pose planning: no candidate pose (" +
                                problem.candidates.Summary() + ")");
  }
  problem.grid = ReachableGridPoses(robot, &problem.unreachable_grid_ids);
  if (problem.grid.empty()) {
    throw std::runtime_error(
        "pose planning: none of the paper's 81 grid poses, over which the accuracy is "
        "predicted, is within the a priori robot's reach: check robot.yaml's lengths");
  }
  std::vector<EePose> poses_B;
  for (const CandidatePose& pose : problem.candidates.poses) poses_B.push_back(pose.x_B);
  for (const PlannedPose& pose : problem.grid) {
    problem.grid_indices.push_back(static_cast<int>(poses_B.size()));
    poses_B.push_back(pose.x);
  }
  problem.info =
      BuildInformationModel(robot, options.model, poses_B, problem.candidate_count(), options.cost);
  return problem;
}

namespace {

// One exchange from options.seed's start.
Design DesignFromOneStart(const PlanningProblem& problem, const DesignOptions& options,
                          PlanCriterion criterion) {
  return criterion == PlanCriterion::kDOptimal
             ? PlanDOptimal(problem.info, problem.candidate_count(), options)
             : PlanForAccuracy(problem.info, problem.candidate_count(), problem.grid_indices,
                               options);
}

// Lower is better: minus log det, or the predicted position RMS over the grid.
double DesignCost(const PlanningProblem& problem, const Design& design, PlanCriterion criterion) {
  return criterion == PlanCriterion::kDOptimal
             ? -design.log_det
             : PredictedPositionRms(problem.info, InformationMatrix(problem.info, design.chosen),
                                    problem.grid_indices);
}

// The best design of options.restarts starts (seeds seed, seed + 1, ...).
Design BestDesign(const PlanningProblem& problem, DesignOptions options, PlanCriterion criterion) {
  const int restarts = options.restarts;
  Design best = DesignFromOneStart(problem, options, criterion);
  double best_cost = DesignCost(problem, best, criterion);
  for (int r = 1; r < restarts; ++r) {
    ++options.seed;
    const Design design = DesignFromOneStart(problem, options, criterion);
    const double cost = DesignCost(problem, design, criterion);
    if (cost < best_cost) {
      best = design;
      best_cost = cost;
    }
  }
  return best;
}

}  // namespace

PlannedCampaign PlanCampaign(const PlanningProblem& problem, const DesignOptions& options,
                             int64_t first_pose_id, PlanCriterion criterion) {
  PlannedCampaign campaign;
  campaign.design = BestDesign(problem, options, criterion);
  int64_t pose_id = first_pose_id;
  for (int j : campaign.design.chosen) {
    campaign.plan.push_back({pose_id++, problem.candidates.poses[static_cast<size_t>(j)].x_B});
  }
  campaign.predicted_position_rms = PredictedPositionRms(
      problem.info, InformationMatrix(problem.info, campaign.design.chosen), problem.grid_indices);
  return campaign;
}

int MinimumPlannedPoses(const PlanningProblem& problem) {
  const int free_parameters = problem.info.parameter_count();
  return std::max(MinimumPosesInFit(free_parameters), (free_parameters + 5) / 6);
}

void CheckPlannedPoseCount(const PlanningProblem& problem, int pose_count) {
  const int needed = MinimumPlannedPoses(problem);
  if (pose_count >= needed) return;
  throw std::invalid_argument(fmt::format(
      "{} poses are too few: Model {} needs at least {} to identify its {} free parameters and "
      "test the fit against the camera noise (identify's verdict would be too_few_poses); "
      "plan {} or more",
      pose_count, ToString(problem.info.model), needed, problem.info.parameter_count(), needed));
}

double GridPredictedPositionRms(const PlanningProblem& problem, int n, uint64_t seed) {
  const int grid_size = static_cast<int>(problem.grid_indices.size());
  std::vector<int> chosen;
  for (int k : SeededSubset(grid_size, std::clamp(n, 0, grid_size), seed)) {
    chosen.push_back(problem.grid_indices[static_cast<size_t>(k)]);
  }
  return PredictedPositionRms(problem.info, InformationMatrix(problem.info, chosen),
                              problem.grid_indices);
}

}  // namespace h4::host
