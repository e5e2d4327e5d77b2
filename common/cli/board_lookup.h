// A bare file name on a command line (`--board aprilgrid_6x6_30mm.yaml`, `--camera
// sim_camera_1024x768.yaml`, as the README's walkthrough writes them) names one of the
// boards and camera files installed with the programs when no such file is in the working
// folder: the walkthrough works from any folder, with installed programs or a build tree.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace h4::cli {

/// Where the installed boards (and the simulated camera's files) are, first match wins:
/// beside the running program as installed (PREFIX/bin/../share/h4cam/boards, then
/// ../share/h4cal/boards: any prefix), the Debian package's /usr/share/h4cam/boards, then
/// ./boards (the source tree, for the programs of a build tree).
std::vector<std::filesystem::path> InstalledBoardFolders();

/// `value` when it is an existing file or a path (it holds a '/'); else the first of
/// folder/NAME and folder/NAME.yaml that is a file; "" when there is none.
std::string ResolveBoardPath(const std::string& value,
                             const std::vector<std::filesystem::path>& folders);

/// CLI11 transform of --board (a check would discard the change): replaces a bare name by
/// the installed board it names; refuses a name found nowhere, saying where it looked.
CLI::Validator ExistingBoardFile(
    const std::vector<std::filesystem::path>& folders = InstalledBoardFolders());

/// The same for --camera, whose file may name one camera of a Kalibr camchain
/// (`camchain.yaml#cam1`: the file is the text before the last '#').
CLI::Validator ExistingCameraFile(
    const std::vector<std::filesystem::path>& folders = InstalledBoardFolders());

}  // namespace h4::cli
