// Clean stop on SIGINT / SIGTERM; see stop_signal.h.
#include "common/cli/stop_signal.h"

#include <csignal>

namespace h4::cli {
namespace {

std::atomic<bool> g_stop_requested{false};

extern "C" void H4OnStopSignal(int signal_number) {
  g_stop_requested.store(true);
  std::signal(signal_number, SIG_DFL);  // async-signal-safe; a second signal is not ignored
}

}  // namespace

const std::atomic<bool>& InstallStopSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = H4OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  return g_stop_requested;
}

}  // namespace h4::cli
