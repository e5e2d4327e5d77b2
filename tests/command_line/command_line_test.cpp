// The command-line conventions both programs share (common/cli/command_line.h,
// shared_options.h): old spellings accepted but not shown, one error line, exit codes.
#include "common/cli/command_line.h"

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/format_error.h"

namespace h4::cli {
namespace {

// A program with one command taking a required --out-dir whose old spelling is --out.
struct Program {
  CLI::App app{"test program"};
  std::string out_dir;
  CLI::App* command = nullptr;

  Program() {
    SetUpProgram(&app, "prog", "1.2.3");
    command = app.add_subcommand("render", "Renders");
    AddOutDirOption(command, &out_dir, "Output folder", "--out")->required();
  }

  int Run(std::vector<std::string> args) {
    std::vector<char*> argv = {program_name.data()};
    for (std::string& arg : args) argv.push_back(arg.data());
    return RunCommandLine(&app, "prog", static_cast<int>(argv.size()), argv.data());
  }

  std::string program_name = "prog";
};

TEST(CommandLineTest, NewAndOldSpellingWriteTheSameOption) {
  Program by_new_name;
  EXPECT_EQ(by_new_name.Run({"render", "--out-dir", "frames"}), 0);
  EXPECT_EQ(by_new_name.out_dir, "frames");
  Program by_old_name;  // the old spelling also satisfies the requirement
  EXPECT_EQ(by_old_name.Run({"render", "--out", "old"}), 0);
  EXPECT_EQ(by_old_name.out_dir, "old");
}

TEST(CommandLineTest, HelpShowsTheNewNameOnly) {
  Program program;
  const std::string help = program.command->help();
  EXPECT_NE(help.find("--out-dir"), std::string::npos) << help;
  EXPECT_EQ(help.find("--out-dir,--out"), std::string::npos) << help;
  EXPECT_EQ(help.find("--out "), std::string::npos) << help;
}

TEST(CommandLineTest, MissingRequiredOptionIsNamedByItsNewName) {
  Program program;
  testing::internal::CaptureStderr();
  const int code = program.Run({"render"});
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_GE(code, 100);  // CLI11's usage errors
  EXPECT_NE(err.find("--out-dir"), std::string::npos) << err;
}

TEST(CommandLineTest, CommandErrorIsOneLineNamingFileLineAndField) {
  Program program;
  program.command->callback(
      [] { throw FormatError("robot.yaml", 12, "model12.h", "expected a number, got 'abc'"); });
  testing::internal::CaptureStderr();
  const int code = program.Run({"render", "--out-dir", "x"});
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, kExitError);
  EXPECT_EQ(err, "prog: error: robot.yaml:12: field 'model12.h': expected a number, got 'abc'\n");
}

// issue 27 point 18: --camera camchain.yaml#cam1 was refused "File does not exist": the
// option checked the whole text as a file. The part before '#' is the file.
TEST(CommandLineTest, TheCameraOptionTakesAKalibrCameraAfterTheFile) {
  const std::string dir = ::testing::TempDir();
  const std::string file = fmt::format("{}h4_camchain_{}.yaml", dir, ::getpid());
  std::ofstream(file) << "cam0: {}\n";
  const auto parses = [](const std::string& value) {
    CLI::App app{"test"};
    std::string camera;
    AddCameraOption(&app, &camera);
    try {
      app.parse(std::vector<std::string>{value, "--camera"});  // CLI11 parses the vector reversed
    } catch (const CLI::ParseError& e) {
      return e.what() + std::string();
    }
    return camera == value ? std::string("ok") : "read '" + camera + "'";
  };
  EXPECT_EQ(parses(file), "ok");
  EXPECT_EQ(parses(file + "#cam1"), "ok");
  EXPECT_NE(parses(dir + "h4_missing.yaml#cam1"), "ok");
  EXPECT_NE(parses(dir + "h4_missing.yaml"), "ok");
  std::remove(file.c_str());
}

// A command's run returns its exit code (RunWhenParsed): nothing printed, and what it did
// stays done; a run that returns nothing exits 0.
TEST(CommandLineTest, ExitCodeOfTheCommandIsReturned) {
  for (const int code : {kExitSuccess, kExitNothingUsable, kExitInterrupted}) {
    Program program;
    auto ran = std::make_shared<std::string>();
    RunWhenParsed(program.command, ran, [code](std::string& what) {
      what = "ran";
      return code;
    });
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    EXPECT_EQ(program.Run({"render", "--out-dir", "x"}), code);
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(*ran, "ran");
  }
  Program returns_nothing;
  RunWhenParsed(returns_nothing.command, std::make_shared<int>(0), [](int& n) { n = 1; });
  EXPECT_EQ(returns_nothing.Run({"render", "--out-dir", "x"}), kExitSuccess);
}

}  // namespace
}  // namespace h4::cli
