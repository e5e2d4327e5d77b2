// Pose planning end to end (`h4cal plan`, the planning studies): the candidate set of a
// robot, camera and board, the information model of the candidates, of the paper's 81-pose
// grid (the campaign planned poses are compared with) and of the target region (where the
// user works: the poses the predicted accuracy is taken over), at the a priori robot and at
// robots drawn from its uncertainty, and the choice of N poses with its predicted accuracy.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/units.h"
#include "host/identification/identification_cost.h"
#include "host/kinematics/pose_plan.h"
#include "host/kinematics/robot_description.h"
#include "host/planning/candidate_poses.h"
#include "host/planning/design_bound.h"
#include "host/planning/information_model.h"
#include "host/planning/pose_design.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

/// The region the user will use the robot in: the plan's accuracy is predicted, and
/// optimised, over a lattice of poses spanning it. Poses outside it may be planned: they
/// are chosen only for what they tell about the robot inside it.
struct TargetRegion {
  /// Centre of the box in B, m: the paper's workspace centre.
  Eigen::Vector3d centre = Eigen::Vector3d(0.0, 0.0, -0.45);
  /// Half extent of the box along x, y, z of B, m: the paper's grid box (200 x 200 x 150 mm).
  Eigen::Vector3d half_extent = Eigen::Vector3d(0.1, 0.1, 0.075);
  double theta_min = RadiansFromDegrees(-20.0);  ///< nacelle angle range, rad: the grid's
  double theta_max = RadiansFromDegrees(20.0);
  int positions_per_axis = 4;  ///< the lattice's positions along each axis, faces included
  int theta_count = 5;         ///< its nacelle angles, ends included

  bool IsValid(std::string* why) const;
};

/// The lattice of `region`: positions_per_axis^3 x theta_count poses in B, z, y, x, theta
/// slowest to fastest, pose ids from 1.
PosePlan TargetPoses(const TargetRegion& region);

/// Robots drawn from the a priori robot's uncertainty, at whose Jacobians the design is
/// judged as well as at the a priori's: the plan is for the robot it will meet, which the
/// a priori only approximates (Bayesian I-optimality, pose_design.h PlanForMeanAccuracy).
struct RobustOptions {
  /// How many robots are drawn (the planned model's geometry, Model 12's or Model 31's,
  /// and placement, true_robot.h); 0: the
  /// a priori alone. The criterion and the prediction average over them and the a priori.
  int robots = 8;
  /// The spreads of the draws, and the first draw's seed: PerturbationOptions' geometry
  /// (what `h4cal simulate` assumes of an a priori), and a camera set up to 3 cm and 3 deg
  /// (one sigma per axis) from the a priori X_BC, a hand-placed camera's (the identification
  /// fits the placement first for such a camera: identification.h). A candidate a drawn
  /// camera does not see whole is left out, so the plan keeps its poses when the camera
  /// is not where robot.yaml says.
  PerturbationOptions spread = {
      .seed = 1000, .camera_translation_std = 0.03, .camera_rotation_std = RadiansFromDegrees(3.0)};
};

struct PlanningProblemOptions {
  ModelKind model = ModelKind::k31;  ///< the identification the poses are planned for
  CandidateOptions candidates;
  CostOptions cost;  ///< the measurement sigmas the information is weighted with
  TargetRegion target;
  RobustOptions robust;
  /// Corner noise of the camera, px: each measured pose's noise is the covariance of the
  /// board pose solved from its corners (pose_noise.h), as the camera module reports it.
  /// 0: cost's constant sigmas for every pose (a dataset without sigma columns); else
  /// within the corners CSV's kCornerSigmaBounds (common/formats/corners_csv.h).
  double corner_sigma_px = 0.0;
  /// Poses measured already, in B (the first batch of a sequential campaign): the plan
  /// completes them, and the prediction counts them.
  std::vector<EePose> existing_poses_B;

  /// corner_sigma_px 0 or within kCornerSigmaBounds (NaN and 1e160 px fell back to the
  /// cost's constant sigmas without a word); `why` names the field and the range.
  bool IsValid(std::string* why) const;
};

struct PlanningProblem {
  CandidateSet candidates;
  /// The paper's 81 poses (GridPosePlan) that the a priori robot reaches: the accuracy is
  /// predicted over them.
  PosePlan grid;
  /// Pose ids (1..81) of the grid poses out of the a priori robot's reach (or of a robot
  /// drawn from its uncertainty), left out of grid.
  std::vector<int64_t> unreachable_grid_ids;
  /// Poses 0 .. candidates.poses.size() - 1 are the candidates, the rest the grid's.
  InformationModel info;
  std::vector<int> grid_indices;  ///< indices of the grid poses in info
  /// Indices in info of the target region's poses that the a priori robot and every drawn
  /// robot reach: the predicted accuracy is the RMS over them.
  std::vector<int> target_indices;
  /// Indices in info of options.existing_poses_B (in every design's information).
  std::vector<int> existing_indices;
  int target_lattice_size = 0;  ///< the region's lattice poses, reached or not
  /// One per drawn robot, the same poses as info (candidates, grid, target).
  std::vector<InformationModel> drawn;
  /// Candidates some drawn robot does not reach, or at which its camera, set up as drawn,
  /// does not see the whole board: left out of candidates.
  int candidates_drawn_robots_miss = 0;
  int candidate_count() const { return static_cast<int>(candidates.poses.size()); }
  /// info, then every drawn robot's: what the accuracy criterion averages over.
  std::vector<const InformationModel*> Models() const;
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
  /// One-sigma board position error predicted over the target region, m: RMS over its poses
  /// and over the a priori and drawn robots (information_model.h).
  double predicted_position_rms = 0.0;
};

/// options.existing is problem.existing_indices (the poses measured already).
PlannedCampaign PlanCampaign(const PlanningProblem& problem, DesignOptions options,
                             int64_t first_pose_id = 1,
                             PlanCriterion criterion = PlanCriterion::kDOptimal);

/// The fewest poses a campaign planned for `problem` may have: below it `h4cal identify`
/// calls the fit too_few_poses (verdict.h: the least poses in a fit, and three residuals per
/// free parameter), and a design with fewer residuals than free parameters predicts nothing.
int MinimumPlannedPoses(const PlanningProblem& problem);

/// The fewest poses a plan should have for its prediction to hold: below it a campaign has
/// no poses to spare, and a few lost (a camera set up elsewhere does not see them, the fit
/// rejects them as outliers) leave it too few to identify, and `h4cal plan` says so.
/// kTrustedPosesPerParameter poses per free parameter: 30 for Model 31's 40, chosen from the
/// robust planning study (docs/results.md#planned-poses-on-robots-the-planner-has-never-seen).
inline constexpr double kTrustedPosesPerParameter = 0.75;
int PosesForATrustedPrediction(const PlanningProblem& problem);

/// Throws std::invalid_argument, saying how many poses the model needs, when `pose_count` is
/// below MinimumPlannedPoses(problem).
void CheckPlannedPoseCount(const PlanningProblem& problem, int pose_count);

/// The one-sigma board position error (m) the poses `chosen` (indices into info) predict over
/// the target region with the existing poses, RMS over its poses and over problem.Models();
/// infinity when the poses do not determine the parameters of one of them.
double PredictedTargetRms(const PlanningProblem& problem, std::vector<int> chosen);

/// What no options.pose_count candidates (with the existing poses, which replace
/// options.existing) can beat: a certified lower bound (design_bound.h, the optimal
/// approximate design of the planner's criterion) on the one-sigma board position error (m)
/// PredictedTargetRms gives any of their designs, sigma_t sqrt(criterion_lower / target
/// poses). *bound (when given) receives the design.
double PredictedTargetRmsBound(const PlanningProblem& problem, BoundOptions options,
                               DesignBound* bound = nullptr);

/// The same prediction for n grid poses drawn with `seed` (n = 71: the paper's calibration
/// poses, 10 held out; at most the reachable grid poses).
double GridPredictedPositionRms(const PlanningProblem& problem, int n, uint64_t seed);

}  // namespace h4::host
