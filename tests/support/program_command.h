// How a test starts one of the project's programs (h4cam, or the test program itself).
#pragma once

#include <string>
#include <vector>

namespace h4::test {

// The argv that runs `command` (program path first, then its arguments). Natively that is
// `command` itself. In a cross build (scripts/cross-build) the emulator ctest runs the tests
// with comes first (CMAKE_CROSSCOMPILING_EMULATOR, passed as H4_TEST_EMULATOR by
// tests/CMakeLists.txt): the host kernel may have no binfmt_misc entry for aarch64 (a
// fresh machine or a chroot has none), and then exec'ing an aarch64 program fails, or a
// shell reads it as a script.
/// Deadlines of tests that wait on a program they started are multiplied by this: 1
/// natively; under the cross build's emulator the camera's image code runs about 5x slower
/// (h4cam run's capture test: 3.2 s natively, 16 s under qemu-aarch64 on the same idle
/// machine), and about twice that again on a loaded one.
#ifdef H4_TEST_EMULATOR
inline constexpr int kEmulationTimeScale = 6;
#else
inline constexpr int kEmulationTimeScale = 1;
#endif

inline std::vector<std::string> ProgramArgv(const std::vector<std::string>& command) {
  std::vector<std::string> argv;
#ifdef H4_TEST_EMULATOR
  std::string word;
  for (const char c : std::string(H4_TEST_EMULATOR)) {
    if (c == ' ') {
      if (!word.empty()) argv.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) argv.push_back(word);
#endif
  argv.insert(argv.end(), command.begin(), command.end());
  return argv;
}

// The same for a shell: the emulator (if any) and the program as one word list (paths here
// have no spaces or shell characters); the caller appends the arguments.
inline std::string ProgramCommand(const std::string& program) {
  std::string command;
  for (const std::string& word : ProgramArgv({program})) {
    command += (command.empty() ? "" : " ") + word;
  }
  return command;
}

}  // namespace h4::test
