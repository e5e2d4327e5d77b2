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
/// batch sees several): the default type picks the overload for these options.
template <typename Options, typename Run = void (*)(const Options&)>
void RunWhenParsed(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  command->callback([options = std::move(options), run] { run(*options); });
}

}  // namespace h4::cli
