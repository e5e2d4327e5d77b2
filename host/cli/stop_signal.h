// SIGINT / SIGTERM for the long-running h4cal commands (collect, sim-robot): the first
// signal asks the loop to stop cleanly (flush, summarise); the default action is restored so
// that a second one ends the process at once.
#pragma once

#include <atomic>

namespace h4::host::cli {

/// Installs the handlers (once) and returns the flag they set.
const std::atomic<bool>& InstallStopSignalHandlers();

}  // namespace h4::host::cli
