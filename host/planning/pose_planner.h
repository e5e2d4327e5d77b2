// Pose planning end to end (`h4cal plan`, the planning study): the candidate set of a
// robot, camera and board, the information model of the candidates and of the paper's
// 81-pose grid (the poses the predicted accuracy is evaluated on, and the campaign planned
// poses are compared with), the D-optimal choice of N poses and its predicted accuracy.
#pragma once

#include <cstdint>
#include <vector>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/robot/robot_description.h"
#include "host/identification/identification_cost.h"
#include "host/planning/candidate_poses.h"
#include "host/planning/information_model.h"
#include "host/planning/pose_design.h"
#include "host/simulation/pose_plan.h"

namespace h4::host {

struct PlanningProblemOptions {
  ModelKind model = ModelKind::k31;  ///< the identification the poses are planned for
  CandidateOptions candidates;
  CostOptions cost;  ///< the measurement sigmas the information is weighted with
};

struct PlanningProblem {
  CandidateSet candidates;
  /// The paper's 81 poses (GridPosePlan) that the a priori robot reaches: the accuracy is
  /// predicted over them.
  PosePlan grid;
  /// Pose ids (1..81) of the grid poses out of the a priori robot's reach, left out of grid.
  std::vector<int64_t> unreachable_grid_ids;
  /// Poses 0 .. candidates.poses.size() - 1 are the candidates, the rest the grid's.
  InformationModel info;
  std::vector<int> grid_indices;  ///< indices of the grid poses in info
  int candidate_count() const { return static_cast<int>(candidates.poses.size()); }
};

/// Throws std::invalid_argument (bad options, no candidates) or std::runtime_error (no grid
/// pose within the a priori robot's reach). Grid poses out of reach are left out and listed
/// in unreachable_grid_ids (a robot shorter than the paper's does not reach its corners).
PlanningProblem MakePlanningProblem(const RobotDescription& robot, const CameraModel& camera,
                                    const BoardModel& board, const PlanningProblemOptions& options);

/// What the exchange maximises: the information (D-optimality, log det M) or the predicted
/// accuracy over the grid's poses (I-optimality, from the D-optimal design). Named by
/// `h4cal plan --criterion`, in this order (host/cli/plan_command.cpp).
enum class PlanCriterion { kDOptimal, kAccuracy };

struct PlannedCampaign {
  PosePlan plan;  ///< the chosen poses in B, pose ids from first_pose_id
  Design design;
  /// One-sigma board position error predicted over the grid's 81 poses, m (information_model.h).
  double predicted_position_rms = 0.0;
};

PlannedCampaign PlanCampaign(const PlanningProblem& problem, const DesignOptions& options,
                             int64_t first_pose_id = 1,
                             PlanCriterion criterion = PlanCriterion::kDOptimal);

/// The fewest poses a campaign planned for `problem` may have: below it `h4cal identify`
/// calls the fit too_few_poses (verdict.h: the least poses in a fit, and three residuals per
/// free parameter), and a design with fewer residuals than free parameters predicts nothing.
int MinimumPlannedPoses(const PlanningProblem& problem);

/// Throws std::invalid_argument, saying how many poses the model needs, when `pose_count` is
/// below MinimumPlannedPoses(problem).
void CheckPlannedPoseCount(const PlanningProblem& problem, int pose_count);

/// The same prediction for n grid poses drawn with `seed` (n = 71: the paper's calibration
/// poses, 10 held out; at most the reachable grid poses).
double GridPredictedPositionRms(const PlanningProblem& problem, int n, uint64_t seed);

}  // namespace h4::host
