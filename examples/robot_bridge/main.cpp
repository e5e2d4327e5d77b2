// h4_robot_bridge: the robot side of a calibration campaign, bridging LCM to a controller
// (docs/robot-bridge.md). Here the controller is the simulated H4 (simulated_controller.h),
// so that the bridge can run a whole campaign beside `h4cam run --source sim`; with a real
// robot, construct your Controller instead of SimulatedH4Controller below and drop the
// board-truth publishing (simulation only).
//   h4_robot_bridge --truth DIR/truth.yaml [--robot DIR/robot.yaml] [--rate 100]
//                   [--lcm-url URL] [--joint-speed 0.5] [--settle-time 0.2]
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <h4msgs/sim_board_truth_t.hpp>
#include <lcm/lcm-cpp.hpp>

#include "common/cli/stop_signal.h"
#include "examples/robot_bridge/robot_bridge.h"
#include "examples/robot_bridge/simulated_controller.h"
#include "messages/channels.h"

namespace {

struct BridgeArgs {
  std::string truth_path;
  std::string robot_path;  ///< default: robot.yaml beside the truth file
  std::string lcm_url;     ///< default: $LCM_DEFAULT_URL, else LCM's default (use ttl=0)
  h4::example::RobotBridgeOptions bridge;
  h4::host::SimulatedControllerOptions robot;
};

/// Simulation only: the true board pose, for `h4cam run --source sim` to render.
void PublishBoardTruth(lcm::LCM& lcm, const h4::example::SimulatedH4Controller& robot,
                       const h4::example::RobotBridge& bridge) {
  h4msgs::sim_board_truth_t truth{};
  truth.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                    std::chrono::system_clock::now().time_since_epoch())
                    .count();
  truth.pose_id = bridge.pose_id();
  const h4::RigidTransform X_CT = robot.true_X_CT();
  const Eigen::Vector4d q_CT = X_CT.quaternion_wxyz().normalized();
  for (int k = 0; k < 3; ++k) truth.translation[k] = X_CT.translation()[k];
  for (int k = 0; k < 4; ++k) truth.quaternion[k] = q_CT[k];
  truth.settled = 0;  // not read by the camera; the joint state carries the settled flag
  lcm.publish(h4::channels::kSimBoardTruth, &truth);
}

int Run(const BridgeArgs& args) {
  const std::string robot_path =
      !args.robot_path.empty()
          ? args.robot_path
          : (std::filesystem::path(args.truth_path).parent_path() / "robot.yaml").string();
  h4::example::SimulatedH4Controller controller(args.truth_path, robot_path, args.robot);
  lcm::LCM lcm(args.lcm_url);
  if (!lcm.good()) {
    fmt::print(stderr, "h4_robot_bridge: cannot open LCM '{}'\n", args.lcm_url);
    return 1;
  }
  h4::example::RobotBridge bridge(lcm, controller, args.bridge);
  // Ctrl-C or SIGTERM stops the bridge after its current tick; a second one ends it at once.
  const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
  fmt::print(stderr, "h4_robot_bridge: simulated H4 ({}), {:.0f} Hz\n", args.truth_path,
             args.bridge.rate_hz);
  bridge.Run(stop, [&] { PublishBoardTruth(lcm, controller, bridge); });
  fmt::print(stderr, "h4_robot_bridge: stopped after {} target(s), {} refused\n",
             static_cast<long long>(bridge.targets_received()),
             static_cast<long long>(bridge.targets_refused()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "h4_robot_bridge: a robot controller on H4_ROBOT_TARGET / H4_JOINT_STATE "
      "(docs/robot-bridge.md); here the simulated H4"};
  BridgeArgs args;
  app.add_option("--truth", args.truth_path, "truth.yaml of `h4cal simulate --out-dir DIR`")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--robot", args.robot_path, "A priori robot.yaml (default beside --truth)")
      ->check(CLI::ExistingFile);
  app.add_option("--rate", args.bridge.rate_hz, "Joint states per second, Hz")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  app.add_option("--lcm-url", args.lcm_url, "LCM URL (default $LCM_DEFAULT_URL)");
  app.add_option("--joint-speed", args.robot.joint_speed, "Simulated joint speed, rad/s")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--settle-time", args.robot.settle_time, "Dwell before at rest, s")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return Run(args);
  } catch (const std::exception& e) {
    fmt::print(stderr, "h4_robot_bridge: error: {}\n", e.what());
    return 1;
  }
}
