// Test helper for UDP multicast tests: the test program runs one of its own tests again
// inside a private network namespace (scripts/in-private-netns: loopback only, with a
// multicast route), so real LCM traffic never reaches a real network.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/program_command.h"

namespace h4::test {

/// True inside the namespace RunChildTestInPrivateNamespace made; the child test skips
/// itself elsewhere.
inline bool InPrivateNamespace() { return std::getenv("H4_IN_NETNS") != nullptr; }

/// Runs this test program's test `child_test` ("Suite.Name") inside a private network
/// namespace with H4_IN_NETNS=1 and a timeout. Skips the calling test where no namespace
/// can be made (scripts/in-private-netns --check exits 77: a chroot without root, a
/// locked-down kernel); else fails it unless the child test ran (not skipped) and passed.
inline void RunChildTestInPrivateNamespace(const std::string& child_test, int timeout_s) {
  const std::string netns = H4_SOURCE_DIR "/scripts/in-private-netns";
  const int check = std::system((netns + " --check > /dev/null 2>&1").c_str());
  if (WIFEXITED(check) && WEXITSTATUS(check) == 77) {
    GTEST_SKIP() << "no private network namespace here (" << netns << " --check)";
  }
  ASSERT_TRUE(WIFEXITED(check) && WEXITSTATUS(check) == 0) << netns << " --check failed";
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  // The output goes to a file, not a pipe: a process the child started and left running
  // (after a failed assertion) would hold a pipe open and hang the read past any timeout.
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() / fmt::format("h4_netns_child_{}.log", getpid());
  const std::string command =
      fmt::format("{} env H4_IN_NETNS=1 timeout -k 5 {} {} --gtest_filter={} > {} 2>&1", netns,
                  timeout_s, ProgramCommand(self), child_test, log.string());
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  const std::string output((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(log);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << "exit " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1)
      << (WIFEXITED(status) && WEXITSTATUS(status) == 124 ? " (timed out)" : "") << ":\n"
      << output;
  EXPECT_NE(output.find("[       OK ] " + child_test), std::string::npos)
      << "the child test did not run or did not pass:\n"
      << output;
}

}  // namespace h4::test
