// How every subcommand of h4cal and h4cam is set up. Each program lists its subcommands in
// one table of CommandEntry (host/cli/commands.cpp, firmware/main.cpp): the name, the line
// --help shows, and the Declare*Command function of the command's own file. That function
// makes the command's options struct, declares the options CLI11 writes into it, and has
// the command run on it once the whole line is parsed (README.md#using-h4cal). The
// struct is shared: it outlives the declaring call, held by the run callback.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>

#include <CLI/CLI.hpp>

namespace h4::cli {

/// One subcommand of a program's command table.
struct CommandEntry {
  const char* name;
  const char* description;  ///< the line --help shows for it
  void (*declare)(CLI::App* command);
};

/// Adds `commands` to `app` in their order (the order --help lists them).
inline void AddCommands(CLI::App& app, std::span<const CommandEntry> commands) {
  for (const CommandEntry& entry : commands) {
    entry.declare(app.add_subcommand(entry.name, entry.description));
  }
}

/// Has `command` call run(options) once the command line is parsed. `run` may name an
/// overloaded function (each h4cal command defines its Run(const ...Options&), and a unity
/// batch sees several): the default type picks the overload for these options. A `run`
/// that returns an int returns the program's exit code (common/cli/command_line.h: 0, or 3
/// when it finished without a usable result, 130 when interrupted): it ends the program
/// through CLI11's CLI::RuntimeError, which RunCommandLine returns without a message. No
/// exit code lives in a global.
template <typename Options, typename Run = void (*)(const Options&)>
void RunWhenParsed(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  command->callback([options = std::move(options), run] {
    if constexpr (std::is_void_v<std::invoke_result_t<Run, Options&>>) {
      run(*options);
    } else {
      const int exit_code = run(*options);
      if (exit_code != 0) throw CLI::RuntimeError(exit_code);
    }
  });
}

/// RunWhenParsed for a command whose run returns its exit code; `run` may name an overload.
template <typename Options, typename Run = int (*)(const Options&)>
void RunWhenParsedForExitCode(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  RunWhenParsed<Options, Run>(command, std::move(options), run);
}

}  // namespace h4::cli
