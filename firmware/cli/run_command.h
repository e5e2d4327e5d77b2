// `h4cam run [--config FILE] [--source libcamera|sim|dir:PATH] [--board B.yaml]
// [--camera C.yaml] [--frames N] [--free-run HZ] [--lcm-url URL] [--camera-id ID]
// [--sim-preset clean|processed]`: the
// camera service (h4cam.service). Answers H4_CAPTURE_REQUEST with H4_BOARD_POSE, sends the
// H4_CAMERA_STATUS heartbeat, stops cleanly on SIGINT/SIGTERM. Flags override the file.
#pragma once

#include <atomic>
#include <iosfwd>
#include <optional>
#include <string>

#include "firmware/service/service_config.h"

namespace CLI {
class App;
}

namespace h4::cam {

/// Command-line values; unset ones keep the configuration file's (or the default).
struct RunArgs {
  std::string config_path;
  std::optional<std::string> source, board_path, camera_path, lcm_url, camera_id;
  std::optional<std::string> auth_key_path;  ///< --auth-key: overrides lcm.auth_key_file
  /// Image formation of `--source sim` (replaces the file's sim: block).
  std::optional<std::string> sim_preset;
  /// The camera `--source sim` renders through (the truth); --camera stays the file the
  /// measurement assumes, so a wrong camera file can be rehearsed.
  std::optional<std::string> sim_camera_path;
  std::optional<int> frames;
  std::optional<double> free_run_hz;
};

/// The configuration file (if any) with the flags applied; throws h4::FormatError naming
/// the file/line/field, or std::runtime_error for an invalid flag value.
ServiceConfig ResolveRunConfig(const RunArgs& args);

/// Runs the service until `stop` becomes true; returns the exit code (0 after a clean
/// stop, 1 when the camera or a file cannot be used: the reason goes to `err` and, when
/// the bus is up, into a STATE_ERROR camera status).
int RunService(const ServiceConfig& config, std::ostream& err, const std::atomic<bool>& stop);

void DeclareRunCommand(CLI::App* command);

}  // namespace h4::cam
