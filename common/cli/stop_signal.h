// SIGINT / SIGTERM for the long-running commands of both programs (h4cal collect and
// sim-robot, h4cam run, capture and preview) and the robot-bridge example: the first signal
// asks the loop to stop cleanly (flush, summarise); the default action is restored so that a
// second one ends the process at once, as a user pressing Ctrl-C twice expects.
#pragma once

#include <atomic>

namespace h4::cli {

/// Installs the handlers and returns the flag they set. Install it before anything slow
/// (opening the camera or the bus), so that an early signal is not a kill.
const std::atomic<bool>& InstallStopSignalHandlers();

}  // namespace h4::cli
