// The stop-signal contract both programs' long-running commands rely on
// (common/cli/stop_signal.h): the first SIGINT or SIGTERM only sets the flag; a second one
// takes the default action. Each case runs in a forked child, whose death is the point.
#include "common/cli/stop_signal.h"

#include <csignal>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace h4::cli {
namespace {

constexpr int kChildSawTheFlag = 7;

/// Runs `body` in a child process and returns its wait status.
template <typename Body>
int StatusOfChild(Body body) {
  const pid_t pid = fork();
  if (pid == 0) _exit(body());
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

class StopSignal : public ::testing::TestWithParam<int> {};

TEST_P(StopSignal, TheFirstSignalOnlySetsTheFlag) {
  const int signal_number = GetParam();
  const int status = StatusOfChild([signal_number] {
    const std::atomic<bool>& stop = InstallStopSignalHandlers();
    if (stop.load()) return 1;
    raise(signal_number);
    return stop.load() ? kChildSawTheFlag : 2;
  });
  ASSERT_TRUE(WIFEXITED(status)) << "the first signal killed the process";
  EXPECT_EQ(WEXITSTATUS(status), kChildSawTheFlag);
}

TEST_P(StopSignal, ASecondSignalEndsTheProcess) {
  const int signal_number = GetParam();
  const int status = StatusOfChild([signal_number] {
    InstallStopSignalHandlers();
    raise(signal_number);
    raise(signal_number);
    return kChildSawTheFlag;  // reached only if the second signal was ignored
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), signal_number);
}

INSTANTIATE_TEST_SUITE_P(IntAndTerm, StopSignal, ::testing::Values(SIGINT, SIGTERM));

}  // namespace
}  // namespace h4::cli
