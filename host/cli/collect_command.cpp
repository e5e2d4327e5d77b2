// `h4cal collect`: the calibration campaign over LCM (issue "Live system", item 3-4): drives
// the robot and the camera through a pose plan (or listens, or reads a recorded log) and
// writes the paired dataset durably; a restarted campaign resumes where it stopped. With
// --sequential FIRST,TOTAL it plans and measures a sequential campaign's two stages
// (collect_stages.h). With --report-dir DIR it then identifies Models 12 and 31, validates
// and writes the report.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/stop_signal.h"
#include "common/cli/subcommand.h"
#include "common/formats/file_output.h"
#include "host/campaign/campaign.h"
#include "host/campaign/control_law.h"
#include "host/cli/calibration_workflow.h"
#include "host/cli/collect_stages.h"
#include "host/cli/plan_noise_options.h"
#include "host/cli/commands.h"
#include "host/cli/identification_print.h"
#include "host/cli/plan_reach.h"
#include "host/cli/progress.h"
#include "host/cli/robot_source.h"
#include "host/cli/validation_inputs.h"
#include "host/formats/identification_result.h"
#include "host/formats/pose_plan_rows.h"
#include "host/formats/poses_csv.h"
#include "host/formats/robot_yaml.h"
#include "host/identification/identification.h"
#include "host/kinematics/model31.h"
#include "host/report/html_report.h"
#include "host/validation/measured_square.h"
#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"

namespace h4::host::cli {
namespace {

struct CollectOptions {
  std::string out_path;
  std::string corners_out_path;  ///< "" = beside out_path (CornersPathBeside)
  std::string plan_path;
  bool manual = false;
  bool passive = false;
  std::string from_log;
  std::string lcm_url;
  std::string auth_key_path;  ///< "" = authentication off
  CampaignOptions campaign;
  std::string identify_dir;
  std::string robot_path;
  std::string controller_path;
  std::string joint_range_deg;          ///< "MIN,MAX" for the plan's check, empty: no limit
  bool dry_run = false;                 ///< check the plan, move nothing
  std::vector<int> sequential;          ///< FIRST,TOTAL of a sequential campaign, empty: one plan
  std::string camera_path, board_path;  ///< what a sequential campaign is planned for
  PlanNoiseOptions plan_noise;          ///< what it is planned for, as `plan` takes it
};

/// How a campaign over one plan ended.
struct CampaignEnd {
  bool interrupted = false;
  bool complete = false;  ///< every planned pose recorded, none skipped; --dry-run: all in reach
  bool dry_run = false;   ///< --dry-run: the plan was checked, nothing moved or measured
};

/// The a priori Model 12 a Model 31 control law maps the planned poses through: the
/// export's own model12 block, else --robot's.
std::optional<Model12Parameters> AprioriModel12For(const std::string& controller_path,
                                                   const std::string& robot_path) {
  if (std::filesystem::path(controller_path).extension() != ".json") {
    return ReadRobotYaml(controller_path).model12;
  }
  if (robot_path.empty()) return std::nullopt;
  return ReadRobotYaml(robot_path).model12;
}

/// The paper's control law (IV.D, the square): inverse kinematics with the parameters of a
/// robot.yaml (a priori, or h4cal export's) or of a result, Model 12 or Model 31: the robot
/// is driven by whichever model the verdict found accurate. The planned poses are in B; a
/// Model 31 takes them in its own base frame B31 (origin at P_1), through the a priori
/// robot's nominal X_B31B (common/README.md#model-31-calibration-model-31-parameters).
CampaignOptions::ControlLaw LoadControlLaw(const std::string& path, const std::string& robot_path) {
  RobotSourceOptions source;
  const bool is_result = std::filesystem::path(path).extension() == ".json";
  (is_result ? source.result_path : source.robot_path) = path;
  source.assembly_robot_path = is_result ? robot_path : "";
  std::string description;
  IdentifiedRobot robot = LoadRobot(source, &description);
  std::optional<RigidTransform> X_B31B;
  if (robot.model->kind() == ModelKind::k31) {
    const std::optional<Model12Parameters> apriori = AprioriModel12For(path, robot_path);
    if (!apriori) {
      throw std::invalid_argument(path +
                                  ": a Model 31 control law needs --robot robot.yaml, the "
                                  "a priori robot whose frame B the planned poses are in");
    }
    X_B31B = NominalX_B31B(*apriori);
  }
  spdlog::info("targets sent as joints from the inverse kinematics of {}", description);
  return InverseKinematicsControlLaw(std::move(robot.model), X_B31B);
}

/// With --robot, names the poses of `plan` the a priori robot cannot take, before it moves;
/// an active campaign then skips them without sending their target (the robot would refuse
/// them, or wait out the settle timeout at them). False for --dry-run: the check was all.
bool CheckPlanBeforeMoving(CollectOptions* options, const PosePlan& plan) {
  if (options->robot_path.empty()) {
    if (options->dry_run || !options->joint_range_deg.empty()) {
      throw std::invalid_argument(
          "--dry-run and --joint-range-deg check the plan against the a priori robot: give "
          "--robot robot.yaml");
    }
    if (options->campaign.mode == CampaignMode::kActive) {
      spdlog::info("the plan is not checked against the robot's reach: give --robot robot.yaml");
    }
    return true;
  }
  // A passive campaign moves nothing: what the robot was sent is in the log already.
  if (options->campaign.mode == CampaignMode::kPassive && !options->dry_run) return true;
  const std::map<int64_t, std::string> unreachable = CheckPlanReach(
      ReadRobotYaml(options->robot_path), plan, ParseJointRange(options->joint_range_deg));
  options->campaign.unreachable = unreachable;
  if (!options->dry_run) {
    for (const auto& [pose_id, why] : unreachable) spdlog::warn("not sent: {}", why);
    return true;
  }
  fmt::print("collect --dry-run: {} of {} planned poses out of the a priori robot's reach{}\n",
             unreachable.size(), plan.size(), unreachable.empty() ? "" : " (not sent):");
  for (const auto& [pose_id, why] : unreachable) fmt::print("  {}\n", why);
  return false;
}

/// LCM's file:// provider, as fast as the log can be read (speed=0): the same messages in
/// the same order as the live run, so the passive rule rebuilds the same rows.
std::string LogUrl(const std::string& path) {
  return "file://" + std::filesystem::absolute(path).string() + "?speed=0";
}

void PrintSummary(const Campaign& campaign, const DatasetJournal& journal,
                  const CornersJournal& corners, const bus::LcmBus& bus, bool interrupted) {
  const CampaignCounters& c = campaign.counters();
  fmt::print("campaign: {} of {} planned poses in {} ({} from an earlier run){}\n",
             journal.rows().size(), campaign.planned_count(), journal.path(),
             journal.resumed_count(), interrupted ? ", interrupted" : "");
  fmt::print("  corners of {} poses in {}\n", corners.pose_count(), corners.path());
  // The poses not sent for the reach check were named when it ran: their ids only here.
  std::vector<int64_t> not_sent;
  for (const SkippedPose& s : campaign.skipped()) {
    if (s.not_sent) {
      not_sent.push_back(s.pose_id);
      continue;
    }
    fmt::print("  skipped pose {}: {}\n", static_cast<long long>(s.pose_id), s.reason);
  }
  if (!not_sent.empty()) {
    fmt::print("  not sent, out of the a priori robot's reach (named above): {}\n",
               PoseIdList(not_sent));
  }
  fmt::print(
      "  messages: {} joint states, {} board poses; not used: {} impossible, "
      "{} non-physical covariance, {} unexpected pose id, {} duplicate, "
      "{} stale joint states, {} unpaired, {} undecodable, {} not authentic; "
      "{} retries\n",
      static_cast<long long>(c.joint_states), static_cast<long long>(c.board_poses),
      static_cast<long long>(c.impossible_values),
      static_cast<long long>(c.nonphysical_covariances),
      static_cast<long long>(c.unexpected_pose_ids), static_cast<long long>(c.duplicates),
      static_cast<long long>(c.stale_joint_states), static_cast<long long>(c.unpaired),
      static_cast<long long>(bus.decode_failures()), static_cast<long long>(bus.auth_failures()),
      static_cast<long long>(c.retries));
  if (interrupted) fmt::print("  run the same command again to resume\n");
}

/// The authentication of --auth-key (nullopt: off). A recorded log is old by definition:
/// its messages' MACs and sequences are checked, not their age.
std::optional<bus::BusAuth> CollectAuth(const CollectOptions& options, bool from_log) {
  bus::AuthOptions auth_options;
  auth_options.check_freshness = !from_log;
  return bus::BusAuthFromKeyFile(options.auth_key_path, auth_options);
}

/// Model 12, then Model 31 from it (paper IV.C), validation and the report, in `dir`; each
/// result printed as `identify` prints it, verdict first. True when a model's verdict is
/// good (else the campaign exits 3, as `identify` does).
bool IdentifyAndReport(const CollectOptions& options, const std::string& command_line) {
  namespace fs = std::filesystem;
  fs::create_directories(options.identify_dir);
  const RobotDescription robot = ReadRobotYaml(options.robot_path);
  const std::vector<DatasetRow> rows = ReadDatasetCsv(options.out_path);
  const std::string result12 = (fs::path(options.identify_dir) / "result12.json").string();
  const std::string result31 = (fs::path(options.identify_dir) / "result31.json").string();
  const auto [m12, m31] = IdentifyModel12Then31(robot, rows, IdentificationOptions{});
  const std::vector<std::string> inputs{options.robot_path, options.out_path};
  WriteResultWithProvenance(result12, m12.result, inputs);
  PrintHeadline(m12);
  spdlog::info("Model 12 result written to {}", result12);
  if (!m12.summary.usable) throw std::runtime_error("Model 12 identification not usable");
  WriteResultWithProvenance(result31, m31.result, inputs);
  PrintHeadline(m31);
  spdlog::info("Model 31 result written to {}", result31);
  ValidationFileOptions files;
  files.robot_path = options.robot_path;
  files.data_path = options.out_path;
  files.result12_path = result12;
  if (m31.summary.usable) files.result31_path = result31;
  // The corners the campaign recorded beside its dataset: the report's camera section.
  AddCornersIfRecorded(options.corners_out_path, options.board_path, options.camera_path, &files);
  const ValidationReport report =
      ValidateAndReport(files, options.identify_dir, command_line, true);
  PrintAccuracyMapLine(report.models.back());
  const bool good12 = m12.verdict == Verdict::kGood;
  const bool good31 = m31.summary.usable && m31.verdict == Verdict::kGood;
  if (good31 || good12) {
    fmt::print("collect: the Model {} result is good: {}\n", good31 ? "31" : "12",
               (good31 ? result31 : result12).c_str());
  } else {
    fmt::print("collect: no model's verdict is good (see the verdicts above)\n");
  }
  return good12 || good31;
}

/// Steps the campaign and drains the bus until the campaign ends, the log ends (from_log)
/// or `stop` is set; true when stopped by `stop`. Throws when LCM keeps failing.
bool RunCampaign(Campaign& campaign, bus::LcmBus& bus, bool from_log, const std::atomic<bool>& stop,
                 Progress& progress) {
  // A signal interrupts LCM's wait (EINTR), which it reports as an error: a stop request
  // (checked first, so that Ctrl-C is an interruption: 130, resumable), or for any other
  // signal a one-off. Only an error that persists is a failed bus.
  constexpr int kMaxConsecutiveBusFailures = 10;
  int consecutive_failures = 0;
  while (campaign.Step(Campaign::Clock::now())) {
    const int handled = bus.Handle(std::chrono::milliseconds(20));
    if (stop.load()) return true;
    if (handled >= 0) {
      consecutive_failures = 0;
    } else if (from_log) {
      return false;  // the end of the log
    } else if (++consecutive_failures >= kMaxConsecutiveBusFailures) {
      throw std::runtime_error(fmt::format("LCM stopped receiving on {} ({} failures in a row)",
                                           bus.url(), consecutive_failures));
    }
    progress.Update(campaign.done_count(), campaign.waiting_for());
  }
  return false;  // every pose recorded or skipped
}

/// The corners of the last poses come right after them (board_corners_t.lcm): listens a
/// little longer for those still missing (up to 1 s live; to the end of a log), then says
/// once which poses have none (an older camera or log sends none; the dataset is whole).
void AwaitLastCorners(Campaign& campaign, bus::LcmBus& bus, bool from_log,
                      const std::atomic<bool>& stop, const std::string& corners_path) {
  const auto until = Campaign::Clock::now() + std::chrono::seconds(1);
  while (!campaign.poses_without_corners().empty() && !stop.load() &&
         Campaign::Clock::now() < until) {
    if (bus.Handle(std::chrono::milliseconds(20)) < 0 && from_log) break;
  }
  const std::vector<int64_t> missing = campaign.poses_without_corners();
  if (missing.empty()) return;
  spdlog::warn(
      "{} of the poses recorded have no corners in {} (a camera or log without {}; their dataset "
      "rows are written): pose {}",
      missing.size(), corners_path, channels::kBoardCorners, fmt::join(missing, ", "));
}

/// One campaign over `plan` into the dataset (resumed when it holds rows already), on its
/// own bus: a sequential campaign runs one per stage.
CampaignEnd RunCampaignOver(const CollectOptions& options, const PosePlan& plan,
                            const std::atomic<bool>& stop) {
  const bool from_log = !options.from_log.empty();
  bus::LcmBus bus(from_log ? LogUrl(options.from_log) : options.lcm_url, bus::WireLimits{},
                  CollectAuth(options, from_log));
  if (!bus.good()) {
    throw std::runtime_error(from_log ? options.from_log + ": cannot open the LCM log"
                                      : bus.error());
  }
  spdlog::info(
      "LCM: {}{}", bus.url(),
      options.auth_key_path.empty() ? "" : ", authenticated with " + options.auth_key_path);
  DatasetJournal journal(options.out_path);
  CornersJournal corners(options.corners_out_path);
  ReconcileWithDataset(journal, corners);
  Campaign campaign(bus, plan, journal, corners, options.campaign);

  Progress progress("collect", campaign.planned_count());
  bool interrupted = RunCampaign(campaign, bus, from_log, stop, progress);
  progress.Finish(campaign.finished() ? "every pose recorded or skipped"
                  : interrupted       ? "interrupted"
                                      : "end of the log");
  if (!interrupted) AwaitLastCorners(campaign, bus, from_log, stop, corners.path());
  interrupted = interrupted || stop.load();
  PrintSummary(campaign, journal, corners, bus, interrupted);
  return {interrupted, campaign.finished() && campaign.skipped().empty()};
}

/// --plan's poses, or the paper's grid; for --dry-run the check is all.
CampaignEnd RunPlannedCampaign(CollectOptions options, const std::atomic<bool>& stop) {
  const PosePlan plan = options.plan_path.empty()
                            ? GridPosePlan()
                            : PosePlanFromRows(ReadPosesCsv(options.plan_path));
  if (plan.empty()) throw std::invalid_argument(options.plan_path + ": the pose plan is empty");
  if (!CheckPlanBeforeMoving(&options, plan)) {
    return {.complete = options.campaign.unreachable.empty(), .dry_run = true};
  }
  return RunCampaignOver(options, plan, stop);
}

/// The rows of the dataset measured at poses of `plan`.
std::vector<DatasetRow> RowsOfPlan(const std::vector<DatasetRow>& rows, const PosePlan& plan) {
  std::set<int64_t> planned;
  for (const PlannedPose& pose : plan) planned.insert(pose.pose_id);
  std::vector<DatasetRow> of_plan;
  for (const DatasetRow& row : rows) {
    if (planned.count(row.pose_id)) of_plan.push_back(row);
  }
  return of_plan;
}

/// The poses of `plan` that `rows` hold.
PosePlan MeasuredPart(const PosePlan& plan, const std::vector<DatasetRow>& rows) {
  std::set<int64_t> measured;
  for (const DatasetRow& row : rows) measured.insert(row.pose_id);
  PosePlan part;
  for (const PlannedPose& pose : plan) {
    if (measured.count(pose.pose_id)) part.push_back(pose);
  }
  return part;
}

/// --sequential FIRST,TOTAL: the first stage planned and measured, then the second planned
/// on the robot the first identifies and measured with it (collect_stages.h); a pose the
/// first stage skipped is not measured again in the second.
CampaignEnd RunStages(CollectOptions options, const std::atomic<bool>& stop) {
  CollectStagesOptions stages;
  ParseStageCounts(options.sequential, &stages);
  stages.robot_path = options.robot_path;
  stages.camera_path = options.camera_path;
  stages.board_path = options.board_path;
  stages.joint_range_deg = options.joint_range_deg;
  stages.dataset_path = options.out_path;
  stages.noise = options.plan_noise;
  const PosePlan first = FirstStagePlan(stages);
  CheckPlanBeforeMoving(&options, first);
  const CampaignEnd first_end = RunCampaignOver(options, first, stop);
  if (first_end.interrupted) return first_end;
  // Only stage 1's rows: a resumed campaign's dataset may hold stage 2's already.
  const std::vector<DatasetRow> first_rows = RowsOfPlan(ReadDatasetCsv(options.out_path), first);
  PosePlan both = MeasuredPart(first, first_rows);
  const PosePlan second = SecondStagePlan(stages, first, first_rows);
  both.insert(both.end(), second.begin(), second.end());
  CheckPlanBeforeMoving(&options, both);
  fmt::print("stage 2 of 2: measuring {} poses beside the {} of stage 1\n", second.size(),
             first_rows.size());
  CampaignEnd end = RunCampaignOver(options, both, stop);
  end.complete = end.complete && first_end.complete;
  return end;
}

/// The options that exclude or need each other.
void CheckOptionCombinations(const CollectOptions& options) {
  if (options.manual && options.passive) {
    throw std::invalid_argument("--manual and --passive exclude each other");
  }
  if (!options.identify_dir.empty() && options.robot_path.empty()) {
    throw std::invalid_argument("--identify needs --robot (the a priori robot.yaml)");
  }
  if (!options.from_log.empty() && !options.lcm_url.empty()) {
    throw std::invalid_argument("--from-log reads the log itself: do not give --lcm-url");
  }
  if (options.sequential.empty()) {
    const bool camera = !options.camera_path.empty(), board = !options.board_path.empty();
    if ((camera || board) && options.identify_dir.empty()) {
      throw std::invalid_argument(
          "--camera and --board are what --sequential plans for and what --report-dir's report "
          "maps the recorded corners through: give one of those, or leave them out");
    }
    if (camera != board) {
      throw std::invalid_argument(
          "--camera and --board go together: the camera h4cam measured with and its board");
    }
    return;
  }
  if (!options.plan_path.empty() || options.passive || !options.from_log.empty() ||
      options.dry_run) {
    throw std::invalid_argument(
        "--sequential plans its own poses and drives the robot: not with --plan, --passive, "
        "--from-log or --dry-run (to check a first stage first: h4cal plan --first-stage, then "
        "collect --dry-run --plan)");
  }
  if (options.robot_path.empty() || options.camera_path.empty() || options.board_path.empty()) {
    throw std::invalid_argument(
        "--sequential plans on the a priori robot, camera and board: give --robot, --camera "
        "and --board");
  }
}

/// The exit code (the footer of DeclareCollectCommand).
int Run(CollectOptions options, const std::string& command_line) {
  CheckOptionCombinations(options);
  const bool from_log = !options.from_log.empty();
  if (!options.controller_path.empty()) {
    if (options.manual || options.passive || from_log) {
      throw std::invalid_argument(
          "--controller drives the robot: not with --manual, --passive "
          "or --from-log");
    }
    options.campaign.control_law = LoadControlLaw(options.controller_path, options.robot_path);
  }
  options.campaign.mode = (options.passive || from_log) ? CampaignMode::kPassive
                          : options.manual              ? CampaignMode::kManual
                                                        : CampaignMode::kActive;
  if (options.corners_out_path.empty()) {
    options.corners_out_path = CornersPathBeside(options.out_path);
  }
  RequireOutputIsNotAnInput({"--corners-out", options.corners_out_path},
                            {{"--out", options.out_path},
                             {"--plan", options.plan_path},
                             {"--from-log", options.from_log}});
  // Before the dataset is locked: a stop signal from then on must end the campaign as an
  // interruption (130, resumable), not kill it with the default action (the
  // second-campaign test interrupted the first right after it took the lock, and 1 run in
  // 20 died of SIGINT).
  const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
  const CampaignEnd end =
      options.sequential.empty() ? RunPlannedCampaign(options, stop) : RunStages(options, stop);
  if (end.interrupted) return h4::cli::kExitInterrupted;
  const bool identified_good =
      end.dry_run || options.identify_dir.empty() || IdentifyAndReport(options, command_line);
  return end.complete && identified_good ? h4::cli::kExitSuccess : h4::cli::kExitNothingUsable;
}

// How each pose is measured: frames, timeouts, retries, pairing.
void AddCampaignOptions(CLI::App* command, CampaignOptions* campaign) {
  h4::cli::AddFramesOption(command, &campaign->frame_count,
                           "Frames averaged per measurement (0: the camera's default)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  h4::cli::AddOptionShowingDefault(command, "--settle-timeout", &campaign->settle_timeout_s,
                                   "Seconds to wait for the robot to settle at a pose",
                                   CLI::PositiveNumber);
  h4::cli::AddOptionShowingDefault(command, "--capture-timeout", &campaign->capture_timeout_s,
                                   "Seconds to wait for a measurement", CLI::PositiveNumber);
  h4::cli::AddOptionShowingDefault(
      command, "--retries", &campaign->retries,
      "Extra attempts per pose (timeouts, moved, partial) before skipping it", CLI::Range(0, 100));
  h4::cli::AddOptionShowingDefault(command, "--pair-tolerance", &campaign->pair_tolerance_s,
                                   "Max seconds between a measurement and its joint reading",
                                   CLI::PositiveNumber);
}

// A sequential campaign's stages, and what they are planned for.
void AddSequentialOptions(CLI::App* command, CollectOptions* options) {
  CLI::Option* sequential =
      command
          ->add_option("--sequential", options->sequential,
                       "A sequential campaign of TOTAL poses: FIRST planned on the a priori "
                       "robot inside the paper's grid box and measured, identified, then the "
                       "rest planned on the identified robot and measured (as h4cal plan --from "
                       "--existing; each stage's plan is written beside --out, and a resumed "
                       "campaign keeps it). Needs --robot, --camera, --board; not with --plan")
          ->delimiter(',')
          ->expected(2);
  // What both stages are planned for, as `plan` takes it (issue 44).
  AddPlanNoiseOptions(command, &options->plan_noise);
  for (const char* name : {"--corner-sigma-px", "--setup-sigma-mm", "--setup-sigma-deg"}) {
    command->get_option(name)->needs(sequential);
  }
  h4::cli::AddCameraOption(command, &options->camera_path,
                           "Camera intrinsics YAML h4cam measured with: the sequential campaign "
                           "is planned for it, and --report-dir's report maps the recorded "
                           "corners through it (with --board)");
  h4::cli::AddBoardOption(command, &options->board_path);
}

}  // namespace

void DeclareCollectCommand(CLI::App* command) {
  const auto options = std::make_shared<CollectOptions>();
  h4::cli::AddOutOption(command, &options->out_path,
                        "Dataset CSV; an existing one is resumed (its poses are not measured "
                        "again)");
  command->add_option(
      "--corners-out", options->corners_out_path,
      "Board corners CSV (pose_id,tag_id,corner,u,v,sigma_px) of the recorded poses, appended "
      "and resumed like the dataset; default beside --out: DIR/STEM.corners.csv");
  h4::cli::AddInputFileOption(command, "--plan", &options->plan_path,
                              "Poses CSV (pose_id,X,Y,Z,theta); default the paper's 81-pose grid");
  command->add_flag("--manual", options->manual,
                    "The operator moves the robot: each pose is measured once the robot has "
                    "moved and settled again; no targets are sent");
  command->add_flag("--passive", options->passive,
                    "Send nothing; pair the measurements and joint states heard (e.g. an "
                    "lcm-logplayer replay)");
  h4::cli::AddInputFileOption(
      command, "--from-log", &options->from_log,
      "Rebuild the dataset from an lcm-logger file (LCM's file:// provider)");
  h4::cli::AddInputFileOption(
      command, "--controller", &options->controller_path,
      "Send joint targets from the inverse kinematics of this robot.yaml, h4cal export's "
      "controller.yaml or result.json, Model 12 or 31 (the paper's control law, e.g. for the "
      "square path; a Model 31 result needs --robot; default: pose targets, the robot's own "
      "controller)");
  h4::cli::AddLcmUrlOption(command, &options->lcm_url);
  h4::cli::AddAuthKeyOption(command, &options->auth_key_path, "off");
  AddCampaignOptions(command, &options->campaign);
  // --report-dir as in identify, validate and report (the old spelling --identify stays).
  command->add_option("--report-dir,--identify", options->identify_dir,
                      "After the campaign: identify Models 12 and 31 (each printed with its "
                      "verdict, as identify prints it; exit 3 when neither is good), validate, "
                      "and write DIR/result12.json, DIR/result31.json, DIR/report.html (needs "
                      "--robot)");
  h4::cli::AddRobotOption(command, &options->robot_path,
                          "A priori robot.yaml: the plan is checked against its reach before "
                          "the robot moves (poses it cannot take are named and not sent); "
                          "needed by --report-dir, and by --controller with a Model 31 result "
                          "(its frame B)");
  AddJointRangeOption(command, &options->joint_range_deg);
  AddSequentialOptions(command, options.get());
  command->add_flag("--dry-run", options->dry_run,
                    "Check the plan against --robot's reach (and --joint-range-deg), print the "
                    "poses out of reach and stop: nothing sent, nothing written (exit 3 when "
                    "some are out of reach)");
  command->footer(
      "Exit codes: 0 every pose recorded, 3 some poses skipped (listed) or, with --dry-run, "
      "out of reach, 130 interrupted (run again to resume), 1 error.");
  // Run takes its options by value (it fills the campaign's control law and mode): named
  // through a lambda, since in a unity batch other files' Run overloads are in scope too.
  RunWithCommandLineWhenParsed(
      command, options,
      [](const CollectOptions& parsed, const std::string& line) { return Run(parsed, line); });
}

}  // namespace h4::host::cli
