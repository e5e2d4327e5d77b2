// `h4cam run [--config FILE] [--source libcamera|sim|dir:PATH] [--board B.yaml]
// [--camera C.yaml] [--frames N] [--free-run HZ] [--lcm-url URL] [--camera-id ID]
// [--sim-preset clean|processed]`: the
// camera service (h4cam.service). Answers H4_CAPTURE_REQUEST with H4_BOARD_POSE, sends the
// H4_CAMERA_STATUS heartbeat, stops cleanly on SIGINT/SIGTERM. Flags override the file.
#pragma once

#include <atomic>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "firmware/service/service_config.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace h4::cam {

/// The command line of `h4cam run`: the configuration file, and each flag bound to the
/// ServiceConfig field it sets (service_config.h holds each option's default and meaning).
/// CLI11 writes a flag into this object's own ServiceConfig; only the flags given are
/// copied over the file's values, after the file is read, whatever their order on the line.
class RunFlags {
 public:
  RunFlags() = default;
  RunFlags(const RunFlags&) = delete;  // the bindings point into this object
  RunFlags& operator=(const RunFlags&) = delete;

  /// Declares the flag that sets `field`: `declare` gets the field to bind CLI11 to and
  /// returns the option it declared.
  template <typename T, typename Declare>
  CLI::Option* Bind(T ServiceConfig::*field, Declare declare) {
    CLI::Option* option = declare(&(given_.*field));
    return WhenGiven(option,
                     [this, field](ServiceConfig* config) { config->*field = given_.*field; });
  }
  /// Has `apply` change the configuration when `option` was given (it may throw
  /// std::invalid_argument for a value it cannot use).
  CLI::Option* WhenGiven(CLI::Option* option, std::function<void(ServiceConfig*)> apply);
  /// Applies the flags given, in the order they were declared.
  void ApplyTo(ServiceConfig* config) const;

  std::string config_path;  ///< --config; "" = every default

 private:
  struct Binding {
    const CLI::Option* option;
    std::function<void(ServiceConfig*)> apply;
  };
  ServiceConfig given_;
  std::vector<Binding> bindings_;
};

/// Declares `h4cam run`'s options on `command`, bound to `flags` (which must outlive it).
void DeclareRunOptions(CLI::App* command, RunFlags* flags);

/// The configuration file (if any) with the flags given applied; throws h4::FormatError
/// naming the file/line/field, or std::invalid_argument for an invalid flag value.
ServiceConfig ResolveRunConfig(const RunFlags& flags);

/// Runs the service until `stop` becomes true; returns the exit code (0 after a clean
/// stop, 1 when the camera or a file cannot be used: the reason goes to `err` and, when
/// the bus is up, into a STATE_ERROR camera status).
int RunService(const ServiceConfig& config, std::ostream& err, const std::atomic<bool>& stop);

void DeclareRunCommand(CLI::App* command);

}  // namespace h4::cam
