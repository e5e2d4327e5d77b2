// `h4cal plan`: choose N calibration poses for the measurement-space identification
// (host/planning/pose_design.h: the predicted accuracy over the target region, averaged over
// robots drawn from the a priori uncertainty, by default, or D-optimality, the information, with
// --criterion d) among the poses the a priori robot reaches with the whole board in the camera's
// image (host/planning/candidate_poses.h); writes them as a poses CSV (common/formats/README.md:
// pose_id,X,Y,Z,theta in B) for `h4cal collect --plan`, prints them with the predicted
// accuracy beside the paper's grid, and with --curve the predicted accuracy against N.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/fmt/fmt.h>
#include <spdlog/fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/file_output.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/cli/plan_noise_options.h"
#include "host/cli/plan_reach.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/formats/pose_plan_rows.h"
#include "host/formats/poses_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/pose_plan.h"
#include "host/planning/pose_planner.h"
#include "host/planning/sequential_plan.h"

namespace h4::host::cli {
namespace {

// --criterion's words, in PlanCriterion's order.
constexpr EnumNames<PlanCriterion, PlanCriterion::kAccuracy> kPlanCriterionNames = {"d",
                                                                                    "accuracy"};

struct PlanCommandOptions {
  std::string robot_path, camera_path, board_path, out_path;
  std::string model = "31";
  std::string criterion = "accuracy";  ///< "accuracy" (I-optimal over the grid) or "d" (D-optimal)
  int pose_count = 25;
  uint64_t seed = 1;
  int64_t first_id = 1;
  std::string joint_range_deg;  ///< "MIN,MAX", empty: no limit
  // CandidateOptions' defaults, in the units of the command line.
  double margin_px = CandidateOptions{}.image_margin_px;
  double max_tilt_deg = DegreesFromRadians(CandidateOptions{}.max_tilt);
  double min_depth = CandidateOptions{}.min_depth, max_depth = CandidateOptions{}.max_depth;
  double step = CandidateOptions{}.position_step;
  double max_theta_gain = CandidateOptions{}.max_theta_gain;
  std::string curve_path;  ///< CSV of predicted accuracy against N, empty: none
  std::vector<int> curve_n = {10, 15, 20, 25, 30, 40, 50, 60, 71};
  /// A verification campaign for `h4cal check` (a few poses): D-optimal, below the
  /// identification's minimum, no accuracy predicted.
  bool for_check = false;
  /// A sequential campaign's first stage: candidates inside the target region only
  /// (FirstStageOptions).
  bool first_stage = false;
  /// The target region (TargetRegion): centre and full size of the box in B, mm, and the
  /// nacelle angle range, deg; the defaults are the paper's grid box.
  std::vector<double> region_centre_mm = {0.0, 0.0, -450.0};
  std::vector<double> region_size_mm = {200.0, 200.0, 150.0};
  std::vector<double> region_theta_deg = {-20.0, 20.0};
  int robust_robots = RobustOptions{}.robots;
  PlanNoiseOptions noise;
  /// A sequential campaign's second stage: the first batch's result and dataset.
  std::string from_result_path, existing_dataset_path;
};

TargetRegion RegionOf(const PlanCommandOptions& o) {
  TargetRegion region;
  for (int k = 0; k < 3; ++k) {
    region.centre[k] = 1e-3 * o.region_centre_mm[static_cast<size_t>(k)];
    region.half_extent[k] = 0.5e-3 * o.region_size_mm[static_cast<size_t>(k)];
  }
  region.theta_min = RadiansFromDegrees(o.region_theta_deg[0]);
  region.theta_max = RadiansFromDegrees(o.region_theta_deg[1]);
  std::string why;
  if (!region.IsValid(&why)) throw std::invalid_argument("--region-*: " + why);
  return region;
}

/// --for-check: candidates only where the robot was calibrated, the paper's grid (its box,
/// theta within its +-20 deg by 10 deg). Beyond it the result extrapolates, and fresh poses
/// of an unchanged robot there failed check (docs/results.md#checking-for-drift-h4cal-check).
void KeepToTheCalibratedRegion(CandidateOptions* candidates) {
  const GridOptions grid;
  candidates->centre = grid.centre.head<3>();
  candidates->half_extent = 0.5 * grid.size;
  const double largest_deg =
      DegreesFromRadians(*std::max_element(grid.theta.begin(), grid.theta.end()));
  const int steps = static_cast<int>(std::round(largest_deg / 10.0));
  candidates->theta.clear();
  for (int k = -steps; k <= steps; ++k) candidates->theta.push_back(RadiansFromDegrees(10.0 * k));
}

PlanningProblemOptions ProblemOptions(const PlanCommandOptions& o) {
  PlanningProblemOptions options;
  options.model = *ParseModelKind(o.model);  // CLI11 checked the text
  options.candidates.image_margin_px = o.margin_px;
  options.candidates.max_tilt = RadiansFromDegrees(o.max_tilt_deg);
  options.candidates.min_depth = o.min_depth;
  options.candidates.max_depth = o.max_depth;
  options.candidates.position_step = o.step;
  options.candidates.max_theta_gain = o.max_theta_gain;
  options.candidates.joint_range = ParseJointRange(o.joint_range_deg);
  if (o.for_check) KeepToTheCalibratedRegion(&options.candidates);
  options.target = RegionOf(o);
  if (o.first_stage) options = FirstStageOptions(options);
  options.robust.robots = o.robust_robots;
  ApplyPlanNoise(o.noise, &options);
  return options;
}

PlanCriterion Criterion(const PlanCommandOptions& o) {
  return *kPlanCriterionNames.ValueNamed(o.criterion);  // CLI11 checked the text
}

// A sequential campaign's plan completes the poses already measured: " <conjunction> the N
// measured" for the lines that speak of the plan, empty for a first campaign.
std::string ExistingPosesClause(const char* conjunction, const PlanningProblem& problem) {
  if (problem.existing_indices.empty()) return "";
  return fmt::format(" {} the {} measured", conjunction, problem.existing_indices.size());
}

void PrintPlan(const PlannedCampaign& campaign, const PlanningProblem& problem, uint64_t seed) {
  fmt::print("planned {} poses (Model {}, {} exchanges{}):\n", campaign.plan.size(),
             ToString(problem.info.model), campaign.design.exchanges,
             campaign.design.converged ? "" : ", stopped before convergence");
  fmt::print("  pose_id    X mm    Y mm    Z mm  theta deg\n");
  for (const PlannedPose& pose : campaign.plan) {
    fmt::print("  {:7} {:>7.1f} {:>7.1f} {:>7.1f} {:>10.1f}\n",
               static_cast<long long>(pose.pose_id), pose.x[0] * 1e3, pose.x[1] * 1e3,
               pose.x[2] * 1e3, DegreesFromRadians(pose.x[3]));
  }
  // The paper holds 10 of its 81 poses out: 71 calibration poses (fewer when the a priori
  // robot does not reach the whole grid).
  const int grid_size = static_cast<int>(problem.grid.size());
  const int grid_calibration = std::max(1, grid_size - 10);
  const double grid_rms = GridPredictedPositionRms(problem, grid_calibration, seed);
  const std::string over =
      problem.drawn.empty()
          ? ""
          : fmt::format(" and over the a priori and {} robots drawn from its uncertainty",
                        problem.drawn.size());
  fmt::print(
      "predicted board position error (one sigma, RMS over {} poses of the target region{}): "
      "{:.4f} mm with these {} poses{}; {:.4f} mm with the grid's {} calibration poses\n",
      problem.target_indices.size(), over, campaign.predicted_position_rms * 1e3,
      campaign.plan.size(), ExistingPosesClause("and", problem), grid_rms * 1e3, grid_calibration);
}

// What no design of as many candidates can beat (host/planning/design_bound.h: the optimal
// approximate design of the same criterion, certified), so that the user sees how close the
// plan is to what is possible, not only to the grid.
void PrintBound(const PlannedCampaign& campaign, const PlanningProblem& problem) {
  DesignBound bound;
  BoundOptions options;
  options.pose_count = static_cast<int>(campaign.plan.size());
  const double lower = PredictedTargetRmsBound(problem, options, &bound);
  fmt::print(
      "no {} poses of these {} candidates{} can predict better than {:.4f} mm over the region "
      "(convex bound, {} candidates in the optimal design's support); this plan: {:.4f} mm\n",
      options.pose_count, problem.candidate_count(), ExistingPosesClause("with", problem),
      lower * 1e3, bound.support.size(), campaign.predicted_position_rms * 1e3);
}

void WriteCurve(const PlanCommandOptions& o, const PlanningProblem& problem) {
  std::string csv = "n,planned_position_rms_m,grid_position_rms_m\n";
  fmt::print("predicted board position error against the number of poses (one sigma, mm):\n");
  fmt::print("      N   planned      grid\n");
  for (int n : o.curve_n) {
    if (n < 1 || n > problem.candidate_count()) continue;
    DesignOptions design;
    design.pose_count = n;
    design.seed = o.seed;
    const double planned = PlanCampaign(problem, design, 1, Criterion(o)).predicted_position_rms;
    const bool grid_has_n = n <= static_cast<int>(problem.grid.size());
    const double grid = grid_has_n ? GridPredictedPositionRms(problem, n, o.seed) : NAN;
    fmt::print("  {:5} {:>9.4f} {:>9.4f}\n", n, planned * 1e3, grid * 1e3);
    csv += fmt::format("{},{:.9g},{}\n", n, planned, grid_has_n ? fmt::format("{:.9g}", grid) : "");
  }
  WriteFileAtomically(o.curve_path, csv);
  spdlog::info("wrote the curve to {}", o.curve_path);
}

// The robot the poses are planned on, and the poses measured already: the a priori alone,
// or (--from, --existing) the robot the first batch identified and that batch's poses.
RobotDescription PlanningRobot(const PlanCommandOptions& o, PlanningProblemOptions* options) {
  const RobotDescription apriori = ReadRobotYaml(o.robot_path);
  if (o.from_result_path.empty() != o.existing_dataset_path.empty()) {
    throw std::invalid_argument(
        "--from and --existing go together: the first batch's result and its dataset");
  }
  if (o.from_result_path.empty()) return apriori;
  const RobotDescription identified =
      IdentifiedDescription(apriori, ReadIdentificationResult(o.from_result_path));
  *options = NextStageOptions(*options, identified, ReadDatasetCsv(o.existing_dataset_path));
  spdlog::info(
      "sequential campaign: planning on the robot of {} (Model {}), completing the {} poses of "
      "{}",
      o.from_result_path, ToString(identified.model31 ? ModelKind::k31 : ModelKind::k12),
      options->existing_poses_B.size(), o.existing_dataset_path);
  return identified;
}

// Says so when the poses are few for the free parameters: a campaign with no poses to spare
// ends too_few_poses when the camera misses a few or the fit rejects them
// (docs/results.md#planned-poses-on-robots-the-planner-has-never-seen).
void WarnWhenThePosesAreFew(const PlanningProblem& problem, int pose_count) {
  const int trusted = PosesForATrustedPrediction(problem);
  if (pose_count >= trusted) return;
  spdlog::warn(
      "{} poses for {} free parameters leave few to spare: a campaign that loses a few (the "
      "camera does not see them, the fit rejects them as outliers) may end too_few_poses; "
      "plan {} or more",
      pose_count, problem.info.parameter_count(), trusted);
}

void Run(const PlanCommandOptions& o) {
  PlanningProblemOptions problem_options = ProblemOptions(o);
  const RobotDescription robot = PlanningRobot(o, &problem_options);
  const CameraModel camera(ReadCameraYaml(o.camera_path));
  const BoardModel board(ReadBoardYaml(o.board_path));
  const PlanningProblem problem = MakePlanningProblem(robot, camera, board, problem_options);
  spdlog::info("{}", problem.candidates.Summary());
  spdlog::info("{} free parameters; fixed by the identifiability analysis: {}",
               problem.info.parameter_count(), problem.info.fixed.size());
  if (!problem.unreachable_grid_ids.empty()) {
    spdlog::warn(
        "{} of the paper's 81 grid poses are out of the a priori robot's reach (grid poses {}): "
        "the accuracy is predicted over the other {}",
        problem.unreachable_grid_ids.size(), fmt::join(problem.unreachable_grid_ids, ", "),
        problem.grid.size());
  }
  const int total = o.pose_count + static_cast<int>(problem.existing_indices.size());
  if (!o.for_check) {
    CheckPlannedPoseCount(problem, total);
    WarnWhenThePosesAreFew(problem, total);
  }
  DesignOptions design;
  design.pose_count = o.pose_count;
  design.seed = o.seed;
  // A check compares a few poses with a result: the poses that tell the parameters apart
  // best (D-optimal, as the check study measured: docs/results.md#checking-for-drift-h4cal-check)
  // also show a change of them best; they identify nothing on their own.
  const PlannedCampaign campaign = PlanCampaign(
      problem, design, o.first_id, o.for_check ? PlanCriterion::kDOptimal : Criterion(o));
  if (o.for_check) {
    WritePosesCsv(o.out_path, RowsFromPosePlan(campaign.plan));
    fmt::print(
        "planned {} poses for h4cal check (D-optimal; a verification campaign: they "
        "identify nothing alone, so no accuracy is predicted)\n",
        campaign.plan.size());
    spdlog::info("wrote {} poses to {}: measure them with h4cal collect --plan, then h4cal check",
                 campaign.plan.size(), o.out_path);
    return;
  }
  if (!std::isfinite(campaign.predicted_position_rms)) {
    throw std::runtime_error(fmt::format(
        "the {} planned poses do not determine the {} free parameters (the predicted error is "
        "infinite): plan more poses, or widen the candidates (--step, --max-tilt-deg, "
        "--joint-range-deg)",
        campaign.plan.size(), problem.info.parameter_count()));
  }
  WritePosesCsv(o.out_path, RowsFromPosePlan(campaign.plan));
  PrintPlan(campaign, problem, o.seed);
  PrintBound(campaign, problem);
  spdlog::info("wrote {} poses to {}", campaign.plan.size(), o.out_path);
  if (!o.curve_path.empty()) WriteCurve(o, problem);
}

// The options of the candidate poses (CandidateOptions): which poses the plan may use.
void AddCandidateOptions(CLI::App* command, PlanCommandOptions* options) {
  AddJointRangeOption(command, &options->joint_range_deg);
  command
      ->add_option("--margin-px", options->margin_px,
                   "Board corners at least this far inside the image, px")
      ->capture_default_str();
  command
      ->add_option("--max-tilt-deg", options->max_tilt_deg,
                   "Largest board tilt from the line of sight, deg")
      ->capture_default_str();
  command->add_option("--min-depth", options->min_depth, "Nearest board depth in focus, m")
      ->capture_default_str();
  command->add_option("--max-depth", options->max_depth, "Farthest board depth in focus, m")
      ->capture_default_str();
  command->add_option("--step", options->step, "Candidate grid step, m")->capture_default_str();
  h4::cli::AddOptionShowingDefault(
      command, "--max-theta-gain", &options->max_theta_gain,
      "Largest |d theta / dq| of a candidate (rad/rad): keeps away from the theta "
      "singularity, where the identification cannot be evaluated",
      CLI::PositiveNumber);
}

// The options of the target region, the drawn robots, the camera noise and a sequential
// campaign's second stage: what the plan is for.
void AddTargetAndRobustOptions(CLI::App* command, PlanCommandOptions* options) {
  command
      ->add_option("--region-centre-mm", options->region_centre_mm,
                   "Centre X,Y,Z of the target region (where the robot will work) in B, mm")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  command
      ->add_option("--region-size-mm", options->region_size_mm,
                   "Full size X,Y,Z of the target region's box, mm (default: the paper's grid)")
      ->delimiter(',')
      ->expected(3)
      ->capture_default_str();
  command
      ->add_option("--region-theta-deg", options->region_theta_deg,
                   "Nacelle angle range MIN,MAX of the target region, deg")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  h4::cli::AddOptionShowingDefault(
      command, "--robust-robots", &options->robust_robots,
      "Robots drawn from the a priori uncertainty the accuracy is averaged over "
      "(0: the a priori alone)",
      CLI::Range(0, 100));
  AddPlanNoiseOptions(command, &options->noise);
  command->add_flag("--first-stage", options->first_stage,
                    "Sequential campaign, first stage: candidates inside the target region only "
                    "(a camera set up centimetres away still sees them); then identify, and "
                    "plan the rest with --from and --existing (h4cal collect --sequential runs "
                    "both stages)");
  command->add_option("--from", options->from_result_path,
                      "Sequential campaign: plan the rest on this result of the first batch "
                      "(with --existing)");
  command->add_option("--existing", options->existing_dataset_path,
                      "Sequential campaign: the first batch's dataset CSV, whose poses the plan "
                      "completes (--count more)");
}

// The candidate grid as --help describes it, from CandidateOptions' defaults.
std::string CandidateGridHelp() {
  const CandidateOptions grid;
  return fmt::format(
      "Candidates: a grid of (X, Y, Z, theta) around ({:g}, {:g}, {:g}) m (+-{:g}, +-{:g}, "
      "+-{:g} mm by {:g}, theta {:g}..{:g} deg by {:g}), away from the singularity where the "
      "joints stop holding theta. The predicted accuracy is the one-sigma board position error "
      "the identification's covariance predicts, RMS over the target region (--region-*) and "
      "over "
      "robots drawn from the a priori uncertainty (--robust-robots).",
      grid.centre.x(), grid.centre.y(), grid.centre.z(), grid.half_extent.x() * 1e3,
      grid.half_extent.y() * 1e3, grid.half_extent.z() * 1e3, grid.position_step * 1e3,
      DegreesFromRadians(grid.theta.front()), DegreesFromRadians(grid.theta.back()),
      DegreesFromRadians(grid.theta[1] - grid.theta[0]));
}

}  // namespace

void DeclarePlanCommand(CLI::App* command) {
  const auto options = std::make_shared<PlanCommandOptions>();
  h4::cli::AddRobotOption(command, &options->robot_path, "A priori robot.yaml (with X_BC, X_TE)")
      ->required();
  h4::cli::AddCameraOption(command, &options->camera_path)->required();
  h4::cli::AddBoardOption(command, &options->board_path)->required();
  h4::cli::AddOutOption(command, &options->out_path, "Output poses CSV");
  // --poses is ik's poses CSV; here it was the count, still accepted.
  h4::cli::AddOptionShowingDefault(command, "--count,--poses", &options->pose_count,
                                   "Number of poses N", CLI::Range(1, 10000));
  h4::cli::AddModelOption(command, &options->model, "Model the poses are planned for");
  h4::cli::AddChoiceOption(command, "--criterion", &options->criterion, kPlanCriterionNames,
                           "d: D-optimal (information); accuracy: the predicted accuracy over "
                           "the grid's poses (I-optimal, from the D-optimal design)")
      ->capture_default_str();
  h4::cli::AddSeedOption(command, &options->seed, "Seed of the exchange's start");
  command->add_option("--first-id", options->first_id, "pose_id of the first pose")
      ->capture_default_str();
  command->add_flag("--for-check", options->for_check,
                    "Plan a verification campaign for h4cal check (e.g. --count 5): D-optimal, "
                    "fewer poses than an identification needs, no accuracy predicted, within "
                    "the region the paper's grid calibrates (its box, theta within +-20 deg)");
  AddCandidateOptions(command, options.get());
  AddTargetAndRobustOptions(command, options.get());
  command->add_option("--curve", options->curve_path,
                      "Also write the predicted accuracy against N (planned and grid) to this CSV");
  command->add_option("--curve-n", options->curve_n, "The N of the curve")->capture_default_str();
  command->footer(CandidateGridHelp());
  h4::cli::RunWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli
