// `h4cal simulate`: a simulated calibration campaign (issue "Host solver", item 6): a true
// robot drawn around an a priori (or the paper's Table 2), the paper's 81-pose grid (or a
// poses CSV), measurement noise; writes the dataset, the a priori robot.yaml, the truth,
// and the held-out poses' true joints and board poses for scoring with `h4cal fk --compare`.
#include <filesystem>
#include <numbers>

#include <spdlog/spdlog.h>

#include "common/board/board_model.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/joints_csv.h"
#include "host/formats/pose_plan_rows.h"
#include "host/formats/poses_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/corner_campaign.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/simulation_folder.h"
#include "host/simulation/true_robot.h"
#include "host/simulation/truth_file.h"
#include "host/validation/straightness.h"

namespace h4::host::cli {
namespace {

struct SimulateOptions {
  bool paper = false;
  std::string truth = "12";
  std::string robot_path;
  std::string plan_path;
  uint64_t seed = 1;
  uint64_t robot_seed = 1;
  double sigma_t_mm = 0.2;
  double sigma_r_deg = 0.03;
  double sigma_q = 2e-5;
  int valid = 10;
  std::string out_dir;
  // The camera at the corner level (common/README.md#identification-from-corners).
  std::string board_path;
  std::string camera_path;       ///< the true camera the corners are projected through
  std::string camera_file_path;  ///< the camera file the poses are solved with
  double sigma_px = 0.05;
};

// With --board: the board's corners through the true camera with pixel noise, each pose
// solved from them with the camera file (which may differ), corners.csv beside the dataset.
SimulatedDataset SimulateThroughCamera(const SimulateOptions& options, const SimulatedRobot& robot,
                                       const PosePlan& plan, const std::filesystem::path& dir) {
  if (options.camera_path.empty()) {
    throw std::invalid_argument("--board simulates the camera's corners: give --camera too");
  }
  const CameraIntrinsics true_camera = ReadCameraYaml(options.camera_path);
  const CameraIntrinsics file_camera =
      options.camera_file_path.empty() ? true_camera : ReadCameraYaml(options.camera_file_path);
  if (file_camera.width != true_camera.width || file_camera.height != true_camera.height) {
    throw std::invalid_argument("--camera-file must describe an image of --camera's size");
  }
  const CornerCampaign campaign = SimulateCornerCampaign(
      robot, plan, BoardModel(ReadBoardYaml(options.board_path)), true_camera, file_camera,
      {.sigma_px = options.sigma_px,
       .sigma_q = options.sigma_q,
       .seed = options.seed,
       .valid_count = options.valid});
  std::filesystem::create_directories(dir);
  WriteCornersCsv(SimulationFolder{dir}.corners(), campaign.corners);
  SimulatedDataset dataset;
  dataset.rows = campaign.rows;
  dataset.truth = campaign.truth;
  return dataset;
}

// The held-out poses' true joints and true board poses: `h4cal fk --result R
// --joints heldout_joints.csv --compare heldout_truth.csv` scores an identification.
// Returns how many poses are held out.
size_t WriteHeldOutTruth(const SimulationFolder& folder, const SimulatedDataset& dataset) {
  std::vector<JointsRow> heldout_joints;
  std::vector<FkRow> heldout_truth;
  for (size_t i = 0; i < dataset.rows.size(); ++i) {
    if (dataset.rows[i].set != PoseSet::kValid) continue;
    const SimulatedPose& t = dataset.truth[i];
    heldout_joints.push_back({.pose_id = t.pose_id, .q = {t.q[0], t.q[1], t.q[2], t.q[3]}});
    heldout_truth.push_back(
        {.pose =
             {.pose_id = t.pose_id, .X = t.x_B[0], .Y = t.x_B[1], .Z = t.x_B[2], .theta = t.x_B[3]},
         .X_CT = t.X_CT});
  }
  WriteJointsCsv(folder.heldout_joints(), heldout_joints);
  WriteFkCsv(folder.heldout_truth(), heldout_truth);
  return heldout_joints.size();
}

void Run(const SimulateOptions& options) {
  namespace fs = std::filesystem;
  const RobotDescription apriori =
      options.robot_path.empty() ? PaperAprioriRobot() : ReadRobotYaml(options.robot_path);
  const TrueGeometry geometry =
      options.paper ? TrueGeometry::kPaperTable2 : *kTrueGeometryNames.ValueNamed(options.truth);
  PerturbationOptions perturbation;
  perturbation.seed = options.robot_seed;
  const SimulatedRobot robot = MakeTrueRobot(apriori, geometry, perturbation);

  const PosePlan plan = options.plan_path.empty()
                            ? GridPosePlan()
                            : PosePlanFromRows(ReadPosesCsv(options.plan_path));
  DatasetOptions dataset_options;
  dataset_options.seed = options.seed;
  dataset_options.valid_count = options.valid;
  dataset_options.noise.sigma_t = options.sigma_t_mm * 1e-3;
  dataset_options.noise.sigma_r = RadiansFromDegrees(options.sigma_r_deg);
  dataset_options.noise.sigma_q = options.sigma_q;
  const fs::path dir(options.out_dir);
  const SimulatedDataset dataset = options.board_path.empty()
                                       ? SimulateDataset(robot, plan, dataset_options)
                                       : SimulateThroughCamera(options, robot, plan, dir);
  if (dataset.rows.empty()) {
    throw std::runtime_error("no planned pose is reachable by the true robot");
  }
  if (static_cast<size_t>(options.valid) > dataset.rows.size()) {
    throw std::invalid_argument(
        fmt::format("--validation {}: only {} poses are planned and reachable", options.valid,
                    dataset.rows.size()));
  }

  fs::create_directories(options.out_dir);
  const SimulationFolder folder{dir};
  WriteDatasetCsv(folder.dataset(), dataset.rows);
  WriteRobotYaml(folder.apriori_robot(), apriori);
  SimulationTruth truth{.robot = robot,
                        .noise = dataset_options.noise,
                        .robot_seed = options.robot_seed,
                        .dataset_seed = options.seed};
  WriteTruthYaml(folder.truth(), truth);

  const size_t heldout = WriteHeldOutTruth(folder, dataset);

  // The straightness experiment (paper IV.D, Table 4): the true robot slides along a
  // straight ruler in two directions while its (noisy) encoders are logged.
  const std::vector<RulerLine> rulers = PaperRulerLines();
  for (size_t k = 0; k < rulers.size(); ++k) {
    const std::string path = folder.straightness(static_cast<int>(k) + 1);
    try {
      WriteJointsCsv(path,
                     SimulateRulerRun(robot, rulers[k], options.sigma_q, options.seed + 1000 + k));
    } catch (const std::invalid_argument& e) {
      spdlog::warn("{} not written: {}", path, e.what());
    }
  }

  spdlog::info("simulated Model {} truth{}: {} poses ({} held out), {} out of reach",
               ToString(robot.truth_model()),
               geometry == TrueGeometry::kPaperTable2 ? " (paper Table 2)" : "",
               dataset.rows.size(), heldout, dataset.unreachable.size());
  spdlog::info(
      "wrote {}/{{dataset.csv, robot.yaml, truth.yaml, heldout_joints.csv, heldout_truth.csv, "
      "straightness_1.csv, straightness_2.csv{}}}",
      options.out_dir, options.board_path.empty() ? "" : ", corners.csv");
}

}  // namespace

void DeclareSimulateCommand(CLI::App* command) {
  const auto options = std::make_shared<SimulateOptions>();
  command->add_flag("--paper", options->paper,
                    "The paper's scenario: Table 2 'Identified' as the true robot, Table 2 a "
                    "priori in robot.yaml (same as --truth-model paper)");
  // --truth names a truth.yaml file in sim-robot and validate; here it was the model.
  h4::cli::AddOptionShowingDefault(
      command, "--truth-model,--truth", &options->truth,
      "True geometry: 12 (a priori Model 12 perturbed), 31 (perturbed joint "
      "positions, axes and lengths), paper (Table 2)",
      h4::cli::OneOf(kTrueGeometryNames));
  h4::cli::AddRobotOption(
      command, &options->robot_path,
      "A priori robot.yaml to draw the truth around (default: the paper's a priori)");
  h4::cli::AddInputFileOption(command, "--plan", &options->plan_path,
                              "Poses CSV pose_id,X,Y,Z,theta (default: the paper's 81-pose grid, "
                              "200x200x150 mm at (0,0,-0.45) m, theta -20/0/20 deg)");
  h4::cli::AddSeedOption(command, &options->seed, "Seed of the noise and of the calib/valid split");
  command->add_option("--robot-seed", options->robot_seed, "Seed of the true robot's perturbation")
      ->capture_default_str();
  h4::cli::AddOptionShowingDefault(command, "--sigma-t-mm", &options->sigma_t_mm,
                                   "Camera translation noise per axis, mm", CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(command, "--sigma-r-deg", &options->sigma_r_deg,
                                   "Camera rotation noise per axis, deg", CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(command, "--sigma-q", &options->sigma_q, "Encoder noise, rad",
                                   CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(command, "--validation", &options->valid,
                                   "Poses held out for validation", CLI::NonNegativeNumber);
  h4::cli::AddBoardOption(command, &options->board_path)
      ->description(
          "Simulate the camera at the corner level on this board: its corners through --camera "
          "with --sigma-px noise, each pose solved from them with --camera-file; writes "
          "corners.csv (the --sigma-t-mm / --sigma-r-deg noise is then not used)");
  h4::cli::AddCameraOption(command, &options->camera_path,
                           "With --board: the true camera the corners are imaged through");
  h4::cli::AddInputFileOption(command, "--camera-file", &options->camera_file_path,
                              "With --board: the camera file the poses are solved with, e.g. one "
                              "as wrong as a real intrinsic calibration (default: --camera)");
  h4::cli::AddOptionShowingDefault(command, "--sigma-px", &options->sigma_px,
                                   "With --board: corner noise per axis, px",
                                   CLI::Range(1e-6, 100.0));
  h4::cli::AddOutDirOption(command, &options->out_dir, "Output folder")->required();
  h4::cli::RunWhenParsed(command, options, Run);
}

}  // namespace h4::host::cli
