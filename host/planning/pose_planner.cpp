// Pose planning end to end (pose_planner.h).
#include "host/planning/pose_planner.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/formats/corners_csv.h"
#include "common/text/invalid_reason.h"
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
  options.noise = NoiseOptions::None();
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

bool TargetRegion::IsValid(std::string* why) const {
  if (!centre.allFinite()) return Invalid(why, "the target region's centre must be finite");
  if (!half_extent.allFinite() || (half_extent.array() < 0.0).any()) {
    return Invalid(why, "the target region's half extent must be finite and >= 0");
  }
  if (!(std::isfinite(theta_min) && std::isfinite(theta_max) && theta_min <= theta_max)) {
    return Invalid(why, "the target region's theta range must be finite with min <= max");
  }
  if (positions_per_axis < 1 || positions_per_axis > 20) {
    return Invalid(why, "the target region's positions_per_axis must be in 1..20");
  }
  if (theta_count < 1 || theta_count > 20) return Invalid(why, "theta_count must be in 1..20");
  return true;
}

namespace {

// count values spanning [low, high], ends included (the middle alone for one).
std::vector<double> Span(double low, double high, int count) {
  if (count == 1) return {0.5 * (low + high)};
  std::vector<double> values;
  for (int k = 0; k < count; ++k) values.push_back(low + (high - low) * k / (count - 1));
  return values;
}

}  // namespace

PosePlan TargetPoses(const TargetRegion& region) {
  std::string why;
  if (!region.IsValid(&why)) throw std::invalid_argument(why);
  std::vector<std::vector<double>> axes;
  for (int k = 0; k < 3; ++k) {
    axes.push_back(Span(region.centre[k] - region.half_extent[k],
                        region.centre[k] + region.half_extent[k], region.positions_per_axis));
  }
  PosePlan poses;
  for (double z : axes[2]) {
    for (double y : axes[1]) {
      for (double x : axes[0]) {
        for (double theta : Span(region.theta_min, region.theta_max, region.theta_count)) {
          poses.push_back({static_cast<int64_t>(poses.size() + 1), EePose(x, y, z, theta)});
        }
      }
    }
  }
  return poses;
}

bool PlanningProblemOptions::IsValid(std::string* why) const {
  if (corner_sigma_px != 0.0 &&
      !(corner_sigma_px >= kCornerSigmaBounds.min && corner_sigma_px <= kCornerSigmaBounds.max)) {
    return Invalid(why,
                   fmt::format("corner_sigma_px must be 0 (none) or in [{:g}, {:g}] px (the "
                               "corners CSV's sigma_px), got {:g}",
                               kCornerSigmaBounds.min, kCornerSigmaBounds.max, corner_sigma_px));
  }
  return true;
}

std::vector<const InformationModel*> PlanningProblem::Models() const {
  std::vector<const InformationModel*> models = {&info};
  for (const InformationModel& model : drawn) models.push_back(&model);
  return models;
}

namespace {

// Whether `robot` reaches each of `poses_B` (its inverse kinematics, as SimulateDataset's).
std::vector<char> ReachedBy(const SimulatedRobot& robot, const std::vector<EePose>& poses_B) {
  PosePlan plan;
  for (size_t j = 0; j < poses_B.size(); ++j) {
    plan.push_back({static_cast<int64_t>(j), poses_B[j]});
  }
  DatasetOptions options;
  options.noise = NoiseOptions::None();
  options.valid_count = 0;
  std::vector<char> reached(poses_B.size(), 1);
  for (int64_t j : SimulateDataset(robot, plan, options).unreachable) {
    reached[static_cast<size_t>(j)] = 0;
  }
  return reached;
}

// The robots of options.robust, drawn around `robot` in the parameterisation of the model
// planned for: each drawn robot's information is that model's at the drawn robot, its rows
// exactly what the model predicts there. Model 31 robots under a Model 12 plan gave rows
// of a Model 31 truth evaluated at the nominal Model 12, whose forward kinematics failed
// at some pose for every robot tried (issue 42, defect 13: plan --model 12 worked only
// with --robust-robots 0).
std::vector<SimulatedRobot> DrawnRobots(const RobotDescription& robot, const RobustOptions& options,
                                        ModelKind model) {
  const TrueGeometry geometry =
      model == ModelKind::k12 ? TrueGeometry::kPerturbedModel12 : TrueGeometry::kPerturbedModel31;
  std::vector<SimulatedRobot> drawn;
  for (int k = 0; k < options.robots; ++k) {
    PerturbationOptions spread = options.spread;
    spread.seed += static_cast<uint64_t>(k);
    drawn.push_back(MakeTrueRobot(robot, geometry, spread));
  }
  return drawn;
}

// The poses every robot of `drawn` reaches, among candidates, grid and target: the others
// are left out of the problem (a grid pose's id goes to unreachable_grid_ids).
void KeepPosesEveryRobotReaches(const std::vector<SimulatedRobot>& drawn, PlanningProblem* problem,
                                PosePlan* target) {
  std::vector<EePose> poses_B;
  for (const CandidatePose& pose : problem->candidates.poses) poses_B.push_back(pose.x_B);
  for (const PlannedPose& pose : problem->grid) poses_B.push_back(pose.x);
  for (const PlannedPose& pose : *target) poses_B.push_back(pose.x);
  std::vector<char> keep(poses_B.size(), 1);
  for (const SimulatedRobot& robot : drawn) {
    const std::vector<char> reached = ReachedBy(robot, poses_B);
    for (size_t j = 0; j < keep.size(); ++j) keep[j] = keep[j] && reached[j];
  }
  size_t j = 0;
  std::vector<CandidatePose> candidates;
  for (const CandidatePose& pose : problem->candidates.poses) {
    if (keep[j++]) candidates.push_back(pose);
  }
  problem->candidates_drawn_robots_miss +=
      static_cast<int>(problem->candidates.poses.size() - candidates.size());
  problem->candidates.poses = std::move(candidates);
  PosePlan grid, kept_target;
  for (const PlannedPose& pose : problem->grid) {
    if (keep[j++]) {
      grid.push_back(pose);
    } else {
      problem->unreachable_grid_ids.push_back(pose.pose_id);
    }
  }
  for (const PlannedPose& pose : *target) {
    if (keep[j++]) kept_target.push_back(pose);
  }
  problem->grid = std::move(grid);
  *target = std::move(kept_target);
}

// The candidates whose board every robot of `drawn` sees whole, by the candidate rule with
// its own camera and board placement: a pose at the image's edge for the a priori set-up
// leaves the image of a camera set up a few centimetres and degrees away.
void KeepCandidatesEveryCameraSees(const std::vector<SimulatedRobot>& drawn,
                                   const CameraModel& camera, const BoardModel& board,
                                   const CandidateOptions& options, PlanningProblem* problem) {
  std::vector<CandidateFilter> filters;
  for (const SimulatedRobot& robot : drawn) {
    filters.emplace_back(robot.Description(), camera, board, options);
  }
  std::vector<CandidatePose> seen;
  for (const CandidatePose& pose : problem->candidates.poses) {
    const bool everyone = std::all_of(filters.begin(), filters.end(), [&](const auto& filter) {
      return filter.Check(pose.x_B, nullptr) == CandidateVerdict::kOk;
    });
    if (everyone) seen.push_back(pose);
  }
  problem->candidates_drawn_robots_miss +=
      static_cast<int>(problem->candidates.poses.size() - seen.size());
  problem->candidates.poses = std::move(seen);
}

// Each pose's camera noise with options.corner_sigma_px (none without it: the cost's
// constant sigmas). The target poses are evaluated, never measured: they keep the cost's
// default sigma_t, which the predicted error is scaled back by.
std::vector<PoseSigma> MeasuredPoseSigmas(const RobotDescription& robot, const CameraModel& camera,
                                          const BoardModel& board,
                                          const PlanningProblemOptions& options,
                                          const std::vector<EePose>& poses_B,
                                          const std::vector<int>& target_indices) {
  if (!(options.corner_sigma_px > 0.0)) return {};
  const PoseSigma fallback{options.cost.default_sigma_t, options.cost.default_sigma_r};
  std::vector<PoseSigma> sigmas =
      PoseSigmasFromCorners(robot, camera, board, poses_B, options.corner_sigma_px, fallback);
  for (int j : target_indices) sigmas[static_cast<size_t>(j)] = fallback;
  return sigmas;
}

}  // namespace

PlanningProblem MakePlanningProblem(const RobotDescription& robot, const CameraModel& camera,
                                    const BoardModel& board,
                                    const PlanningProblemOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("pose planning: " + why);
  PlanningProblem problem;
  problem.candidates = MakeCandidateSet(robot, camera, board, options.candidates);
  problem.grid = ReachableGridPoses(robot, &problem.unreachable_grid_ids);
  PosePlan target = TargetPoses(options.target);
  problem.target_lattice_size = static_cast<int>(target.size());
  std::vector<SimulatedRobot> drawn = DrawnRobots(robot, options.robust, options.model);
  drawn.insert(drawn.begin(), SimulatedRobot::FromDescription(robot));  // the a priori too
  KeepPosesEveryRobotReaches(drawn, &problem, &target);
  KeepCandidatesEveryCameraSees(drawn, camera, board, options.candidates, &problem);
  if (problem.candidates.poses.empty()) {
    throw std::invalid_argument("pose planning: no candidate pose (" +
                                problem.candidates.Summary() + ")");
  }
  if (problem.grid.empty() || target.empty()) {
    throw std::runtime_error(
        "pose planning: none of the paper's 81 grid poses, or none of the target region's "
        "poses, over which the accuracy is predicted, is within the a priori robot's reach: "
        "check robot.yaml's lengths and the region");
  }
  std::vector<EePose> poses_B;
  for (const CandidatePose& pose : problem.candidates.poses) poses_B.push_back(pose.x_B);
  for (const PlannedPose& pose : problem.grid) {
    problem.grid_indices.push_back(static_cast<int>(poses_B.size()));
    poses_B.push_back(pose.x);
  }
  for (const PlannedPose& pose : target) {
    problem.target_indices.push_back(static_cast<int>(poses_B.size()));
    poses_B.push_back(pose.x);
  }
  for (const EePose& x_B : options.existing_poses_B) {
    problem.existing_indices.push_back(static_cast<int>(poses_B.size()));
    poses_B.push_back(x_B);
  }
  const int analysed = problem.candidate_count();
  const std::vector<PoseSigma> sigmas =
      MeasuredPoseSigmas(robot, camera, board, options, poses_B, problem.target_indices);
  problem.info =
      BuildInformationModel(robot, options.model, poses_B, analysed, options.cost, sigmas);
  for (size_t k = 1; k < drawn.size(); ++k) {
    problem.drawn.push_back(BuildInformationModel(drawn[k].Description(), options.model, poses_B,
                                                  analysed, options.cost, sigmas));
  }
  return problem;
}

namespace {

// One exchange from options.seed's start.
Design DesignFromOneStart(const PlanningProblem& problem, const DesignOptions& options,
                          PlanCriterion criterion) {
  return criterion == PlanCriterion::kDOptimal
             ? PlanDOptimal(problem.info, problem.candidate_count(), options)
             : PlanForMeanAccuracy(problem.Models(), problem.candidate_count(),
                                   problem.target_indices, options);
}

// Lower is better: minus log det, or the predicted position RMS over the target region.
double DesignCost(const PlanningProblem& problem, const Design& design, PlanCriterion criterion) {
  return criterion == PlanCriterion::kDOptimal ? -design.log_det
                                               : PredictedTargetRms(problem, design.chosen);
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

PlannedCampaign PlanCampaign(const PlanningProblem& problem, DesignOptions options,
                             int64_t first_pose_id, PlanCriterion criterion) {
  options.existing = problem.existing_indices;
  PlannedCampaign campaign;
  campaign.design = BestDesign(problem, options, criterion);
  int64_t pose_id = first_pose_id;
  for (int j : campaign.design.chosen) {
    campaign.plan.push_back({pose_id++, problem.candidates.poses[static_cast<size_t>(j)].x_B});
  }
  campaign.predicted_position_rms = PredictedTargetRms(problem, campaign.design.chosen);
  return campaign;
}

int MinimumPlannedPoses(const PlanningProblem& problem) {
  const int free_parameters = problem.info.parameter_count();
  return std::max(MinimumPosesInFit(free_parameters), (free_parameters + 5) / 6);
}

int PosesForATrustedPrediction(const PlanningProblem& problem) {
  return std::max(
      MinimumPlannedPoses(problem),
      static_cast<int>(std::ceil(kTrustedPosesPerParameter * problem.info.parameter_count())));
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

namespace {

// The RMS over the target region and problem.Models() of what the poses `measured` predict.
double TargetRmsOf(const PlanningProblem& problem, const std::vector<int>& measured) {
  double sum_variance = 0.0;
  const std::vector<const InformationModel*> models = problem.Models();
  for (const InformationModel* info : models) {
    const double rms =
        PredictedPositionRms(*info, InformationMatrix(*info, measured), problem.target_indices);
    sum_variance += rms * rms;
  }
  return std::sqrt(sum_variance / static_cast<double>(models.size()));
}

}  // namespace

double GridPredictedPositionRms(const PlanningProblem& problem, int n, uint64_t seed) {
  const int grid_size = static_cast<int>(problem.grid_indices.size());
  std::vector<int> chosen;
  for (int k : SeededSubset(grid_size, std::clamp(n, 0, grid_size), seed)) {
    chosen.push_back(problem.grid_indices[static_cast<size_t>(k)]);
  }
  return TargetRmsOf(problem, chosen);
}

double PredictedTargetRms(const PlanningProblem& problem, std::vector<int> chosen) {
  chosen.insert(chosen.end(), problem.existing_indices.begin(), problem.existing_indices.end());
  return TargetRmsOf(problem, chosen);
}

double PredictedTargetRmsBound(const PlanningProblem& problem, BoundOptions options,
                               DesignBound* bound) {
  options.existing = problem.existing_indices;
  const DesignBound design = OptimalDesignBound(problem.Models(), problem.candidate_count(),
                                                problem.target_indices, options);
  if (bound) *bound = design;
  // PredictedPositionRms's scaling: the criterion is mean_k trace(A_k S_k^-1), the sum over
  // the target poses of their variance in sigma_t units.
  const double target_poses = static_cast<double>(problem.target_indices.size());
  return problem.info.sigma_t * std::sqrt(design.criterion_lower / target_poses);
}

}  // namespace h4::host
