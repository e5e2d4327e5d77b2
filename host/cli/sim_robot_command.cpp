// `h4cal sim-robot`: a simulated H4 controller on LCM for campaigns
// without hardware. It takes H4_ROBOT_TARGET targets, moves the TRUE robot (a truth file
// of `h4cal simulate`, or the paper's Table 2) at finite joint speed, and publishes
// H4_JOINT_STATE at the rate and the true board pose on H4_SIM_BOARD_TRUTH for
// `h4cam run --source sim`. Pose targets go through the A PRIORI model's inverse
// kinematics, as on the real controller, so the campaign sees the a priori model's errors.
#include <atomic>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include <spdlog/spdlog.h>

#include "common/cli/shared_options.h"
#include "common/cli/stop_signal.h"
#include "common/cli/subcommand.h"
#include "host/campaign/sim_robot_node.h"
#include "host/campaign/simulated_controller.h"
#include "host/cli/commands.h"
#include "host/cli/plan_reach.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/paper_robot.h"
#include "host/simulation/true_robot.h"
#include "host/simulation/truth_file.h"
#include "messages/bus/lcm_bus.h"

namespace h4::host::cli {
namespace {

struct SimRobotArgs {
  std::string truth_path;
  std::string robot_path;
  bool paper = false;
  uint64_t robot_seed = 1;
  SimulatedControllerOptions controller;
  std::string joint_range_deg;  ///< --joint-range-deg MIN,MAX, as plan and collect take it
  SimRobotNodeOptions node;
  std::string lcm_url;
  double duration_s = 0.0;
};

struct Scenario {
  SimulatedRobot truth;
  RobotDescription apriori;
  std::string description;
};

Scenario LoadScenario(const SimRobotArgs& args) {
  namespace fs = std::filesystem;
  Scenario scenario;
  if (args.paper) {
    scenario.apriori = PaperAprioriRobot();
    PerturbationOptions placement;
    placement.seed = args.robot_seed;
    scenario.truth = MakeTrueRobot(scenario.apriori, TrueGeometry::kPaperTable2, placement);
    scenario.description =
        fmt::format("paper scenario (Table 2 truth, placement seed {})", args.robot_seed);
    return scenario;
  }
  if (args.truth_path.empty()) {
    throw std::runtime_error(
        "sim-robot: no true robot: give --truth truth.yaml (written by `h4cal simulate "
        "--out-dir DIR`) or --paper");
  }
  scenario.truth = ReadTruthYaml(args.truth_path).robot;
  std::string robot_path = args.robot_path;
  if (robot_path.empty()) {
    const fs::path beside = fs::path(args.truth_path).parent_path() / "robot.yaml";
    if (!fs::exists(beside)) {
      throw std::runtime_error("sim-robot: no a priori robot: " + beside.string() +
                               " (beside the truth file) does not exist; give --robot robot.yaml");
    }
    robot_path = beside.string();
  }
  scenario.apriori = ReadRobotYaml(robot_path);
  scenario.description = "truth " + args.truth_path + " (Model " +
                         std::string(ToString(scenario.truth.truth_model())) + "), a priori " +
                         robot_path;
  return scenario;
}

void Run(const SimRobotArgs& args) {
  // Before the slow set-up, so that an early SIGTERM is a clean stop, not a kill; the node's
  // loop polls the flag at least every 100 ms.
  const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
  const Scenario scenario = LoadScenario(args);
  SimulatedControllerOptions controller_options = args.controller;
  controller_options.joint_limits = ParseJointRange(args.joint_range_deg);
  SimulatedController controller(scenario.truth, scenario.apriori.model12,
                                 scenario.apriori.assembly, controller_options);
  bus::LcmBus bus(args.lcm_url);
  if (!bus.good()) throw std::runtime_error("sim-robot: " + bus.error());
  SimRobotNode node(bus, controller, args.node);

  spdlog::info("sim-robot: {}; LCM {}; {} Hz, joint speed {} rad/s, settle {} s, sigma_q {} rad",
               scenario.description, bus.url(), args.node.rate_hz, args.controller.joint_speed,
               args.controller.settle_time, args.controller.sigma_q);
  // A rehearsal on LCM's default group is heard by every LCM program of the machine, and
  // hears theirs (issue 43 point 6: another campaign on the host was heard).
  if (bus.url() == bus::kDefaultLcmUrl) {
    spdlog::warn(
        "sim-robot: on LCM's default group, which every LCM program on this machine shares: "
        "to keep a rehearsal to itself, set LCM_DEFAULT_URL to a group of its own in every "
        "terminal (README.md, walkthrough step 8), or run inside scripts/in-private-netns");
  }
  node.Run(stop, std::chrono::duration<double>(args.duration_s));
  spdlog::info(
      "sim-robot: stopped after {} target(s) ({} refused), {} joint states, {} bad "
      "message(s)",
      node.targets_received(), node.targets_refused(), node.joint_states_published(),
      bus.decode_failures());
  if (node.bus_failed()) throw std::runtime_error("sim-robot: LCM failed on " + bus.url());
}

}  // namespace

void DeclareSimRobotCommand(CLI::App* command) {
  const auto args = std::make_shared<SimRobotArgs>();
  CLI::Option* truth =
      h4::cli::AddInputFileOption(command, "--truth", &args->truth_path,
                                  "True robot: truth.yaml written by `h4cal simulate --out-dir "
                                  "DIR`");
  h4::cli::AddRobotOption(command, &args->robot_path,
                          "A priori robot.yaml the controller believes (pose targets go through "
                          "its inverse kinematics); default: robot.yaml beside the truth file")
      ->needs(truth);
  CLI::Option* paper = command->add_flag(
      "--paper", args->paper,
      "Paper scenario: Table 2 'Identified' as the truth, Table 2 a priori as the controller's "
      "model (what `h4cal simulate --paper` draws)");
  paper->excludes(truth);
  command
      ->add_option("--robot-seed", args->robot_seed,
                   "With --paper: seed of the true camera and board placement")
      ->capture_default_str();
  h4::cli::AddOptionShowingDefault(
      command, "--joint-speed", &args->controller.joint_speed,
      "Speed of the joint with the farthest to go, rad/s (all arrive together)",
      CLI::PositiveNumber);
  h4::cli::AddOptionShowingDefault(command, "--settle-time", &args->controller.settle_time,
                                   "Time at rest at the target before reporting settled, s",
                                   CLI::NonNegativeNumber);
  h4::cli::AddOptionShowingDefault(command, "--sigma-q", &args->controller.sigma_q,
                                   "Encoder noise per reading, rad", CLI::NonNegativeNumber);
  command
      ->add_option("--joint-range", args->controller.joint_range,
                   "Joint limits: farthest a joint target may be from its home value, rad "
                   "(before --joint-range-deg; kept for scripts)")
      ->check(CLI::PositiveNumber)
      ->group("");
  // The same option, unit and meaning as plan's and collect's: the controller refuses what
  // the plan was checked against.
  AddJointRangeOption(command, &args->joint_range_deg);
  h4::cli::AddSeedOption(command, &args->node.seed, "Seed of the encoder noise");
  h4::cli::AddOptionShowingDefault(command, "--rate", &args->node.rate_hz,
                                   "Joint states (and board truths) published per second, Hz",
                                   CLI::Range(0.1, 10000.0));
  h4::cli::AddOptionShowingDefault(command, "--status-period", &args->node.status_period_s,
                                   "Seconds between status lines on stderr (0: none)",
                                   CLI::NonNegativeNumber);
  h4::cli::AddLcmUrlOption(command, &args->lcm_url);
  h4::cli::AddOptionShowingDefault(command, "--duration", &args->duration_s,
                                   "Run this many seconds (0: until SIGINT or SIGTERM)",
                                   CLI::NonNegativeNumber);
  h4::cli::RunWhenParsed(command, args, Run);
}

}  // namespace h4::host::cli
