// How every subcommand of h4cal and h4cam is set up: CLI11 writes what it parses into the
// command's options struct, and the command runs on that struct once the whole line is
// parsed (README.md, "Using h4cal"). The struct outlives the Add*Command call that
// declares the options, so the command and its callback share it.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace h4::cli {

/// A subcommand and the options struct its options write into.
template <typename Options>
struct Subcommand {
  CLI::App* command;
  std::shared_ptr<Options> options;
};

/// Adds subcommand `name` to `app`, with a default-constructed options struct.
template <typename Options>
Subcommand<Options> AddSubcommand(CLI::App& app, const std::string& name,
                                  const std::string& description) {
  return {app.add_subcommand(name, description), std::make_shared<Options>()};
}

/// Has `command` call run(options) once the command line is parsed. `run` may name an
/// overloaded function (each h4cal command defines its Run(const ...Options&), and a unity
/// batch sees several): the default type picks the overload for these options.
template <typename Options, typename Run = void (*)(const Options&)>
void RunWhenParsed(CLI::App* command, std::shared_ptr<Options> options, Run run) {
  command->callback([options = std::move(options), run] { run(*options); });
}

}  // namespace h4::cli
