// Pose planning end to end (pose_planner.h).
#include "host/planning/pose_planner.h"

#include <stdexcept>

namespace h4::host {

PlanningProblem MakePlanningProblem(const RobotDescription& robot, const CameraModel& camera,
                                    const BoardModel& board,
                                    const PlanningProblemOptions& options) {
  PlanningProblem problem;
  problem.candidates = MakeCandidateSet(robot, camera, board, options.candidates);
  if (problem.candidates.poses.empty()) {
    throw std::invalid_argument("pose planning: no candidate pose (" +
                                problem.candidates.Summary() + ")");
  }
  problem.grid = GridPosePlan();
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

double GridPredictedPositionRms(const PlanningProblem& problem, int n, uint64_t seed) {
  std::vector<int> chosen;
  for (int k : SeededSubset(static_cast<int>(problem.grid_indices.size()), n, seed)) {
    chosen.push_back(problem.grid_indices[static_cast<size_t>(k)]);
  }
  return PredictedPositionRms(problem.info, InformationMatrix(problem.info, chosen),
                              problem.grid_indices);
}

}  // namespace h4::host
