// The options several commands of h4cal and h4cam take, declared once so that the same
// thing has the same name everywhere (README.md#using-h4cal, lists every option). The
// rule: --out a file the command writes, --out-dir the folder it writes its files into,
// --report-dir the folder of an extra report.html; input files by what they hold
// (--robot, --data, --result, --board, --camera); --frames the frames averaged per
// measurement; a name carries its unit when it is not SI (--square-mm, --joint-range-deg).
// Old spellings follow the new name (command_line.h: accepted, not shown in --help).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli/board_lookup.h"
#include "common/text/enum_names.h"

namespace h4::cli {

/// The check that a value is one of the names of `choices` (--help lists them as {a,b}).
template <typename Enum, Enum kLast>
CLI::IsMember OneOf(const EnumNames<Enum, kLast>& choices) {
  return CLI::IsMember(std::vector<std::string>(choices.names().begin(), choices.names().end()));
}

/// An option taking one of the names of `choices` (CLI11 checks it); the command turns the
/// text into the enum with choices.ValueNamed.
template <typename Enum, Enum kLast>
CLI::Option* AddChoiceOption(CLI::App* command, const std::string& names, std::string* text,
                             const EnumNames<Enum, kLast>& choices, const std::string& what) {
  return command->add_option(names, *text, what)->check(OneOf(choices));
}

/// An input file option (checked to exist); `names` as CLI11 takes them ("--new,--old").
template <typename Path>
CLI::Option* AddInputFileOption(CLI::App* command, const std::string& names, Path* path,
                                const std::string& what) {
  return command->add_option(names, *path, what)->check(CLI::ExistingFile);
}

template <typename Path>
CLI::Option* AddRobotOption(CLI::App* command, Path* path,
                            const std::string& what = "A priori robot.yaml") {
  return AddInputFileOption(command, "--robot", path, what);
}

template <typename Path>
CLI::Option* AddDataOption(CLI::App* command, Path* path,
                           const std::string& what = "Paired dataset CSV") {
  return AddInputFileOption(command, "--data", path, what);
}

template <typename Path>
CLI::Option* AddResultOption(CLI::App* command, Path* path,
                             const std::string& what = "Identification result JSON") {
  return AddInputFileOption(command, "--result", path, what);
}

/// --board FILE, or the name of an installed board (board_lookup.h).
template <typename Path>
CLI::Option* AddBoardOption(CLI::App* command, Path* path) {
  return command->add_option("--board", *path, "Board YAML, or an installed board's name")
      ->transform(ExistingBoardFile());
}

template <typename Path>
CLI::Option* AddCameraOption(CLI::App* command, Path* path,
                             const std::string& what =
                                 "Camera intrinsics YAML (OpenCV, or Kalibr's "
                                 "camchain.yaml#camN)") {
  // A file, FILE#camN of a Kalibr camchain, or an installed camera file's name (board_lookup.h).
  return command->add_option("--camera", *path, what)->transform(ExistingCameraFile());
}

/// --out FILE, required: the file the command writes.
template <typename Path>
CLI::Option* AddOutOption(CLI::App* command, Path* path, const std::string& what) {
  return command->add_option("--out", *path, what)->required();
}

/// --out-dir DIR (old spelling --out on the commands whose --out was a folder).
template <typename Path>
CLI::Option* AddOutDirOption(CLI::App* command, Path* dir, const std::string& what,
                             const std::string& old_names = "") {
  return command->add_option("--out-dir" + (old_names.empty() ? "" : "," + old_names), *dir, what);
}

/// --report-dir DIR (old spelling --report): also write DIR/report.html.
template <typename Path>
CLI::Option* AddReportDirOption(CLI::App* command, Path* dir) {
  return command->add_option("--report-dir,--report", *dir, "Also write DIR/report.html");
}

/// An option bound to a field of a library's Options struct, whose initial value is the one
/// default: --help shows it. `check` validates the value (CLI11's validators).
template <typename Field>
CLI::Option* AddOptionShowingDefault(CLI::App* command, const std::string& names, Field* field,
                                     const std::string& help, const CLI::Validator& check) {
  return command->add_option(names, *field, help)->check(check)->capture_default_str();
}

/// --frames N: frames averaged per measurement.
template <typename Count>
CLI::Option* AddFramesOption(CLI::App* command, Count* frames, const std::string& what,
                             const std::string& old_names = "") {
  return command->add_option("--frames" + (old_names.empty() ? "" : "," + old_names), *frames,
                             what);
}

/// --model 12|31: the kinematic model (common/README.md); its default is shown.
template <typename Model>
CLI::Option* AddModelOption(CLI::App* command, Model* model, const std::string& what) {
  return command->add_option("--model", *model, what)
      ->check(CLI::IsMember({"12", "31"}))
      ->capture_default_str();
}

template <typename Seed>
CLI::Option* AddSeedOption(CLI::App* command, Seed* seed, const std::string& what) {
  return command->add_option("--seed", *seed, what)->capture_default_str();
}

template <typename Url>
CLI::Option* AddLcmUrlOption(CLI::App* command, Url* url) {
  return command->add_option("--lcm-url", *url,
                             "LCM provider URL (default $LCM_DEFAULT_URL, else the default "
                             "group with ttl=0)");
}

/// --auth-key FILE; the reader names the file when it is missing or others can read it.
template <typename Path>
CLI::Option* AddAuthKeyOption(CLI::App* command, Path* path, const std::string& default_text) {
  return command->add_option("--auth-key", *path,
                             "Authenticate board poses, capture requests and camera status with "
                             "this pre-shared key file (owner-only, >= 32 bytes; the same on the "
                             "camera, lcm.auth_key_file): other messages on those channels are "
                             "dropped and counted. Default " +
                                 default_text);
}

}  // namespace h4::cli
