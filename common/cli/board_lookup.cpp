// Looking a bare board or camera file name up among the installed ones; see board_lookup.h.
#include "common/cli/board_lookup.h"

#include <system_error>

namespace h4::cli {
namespace {

namespace fs = std::filesystem;

bool IsFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

std::string NotFound(const std::string& name, const std::vector<fs::path>& folders) {
  std::string list;
  for (const fs::path& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  return "File does not exist: " + name + " (nor a file of that name in " + list + ")";
}

}  // namespace

std::vector<fs::path> InstalledBoardFolders() {
  std::vector<fs::path> folders;
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path prefix = program.parent_path().parent_path();
    folders.push_back(prefix / "share/h4cam/boards");
    folders.push_back(prefix / "share/h4cal/boards");
  }
  const fs::path packaged = "/usr/share/h4cam/boards";
  if (folders.empty() || folders.front() != packaged) folders.push_back(packaged);
  folders.push_back("boards");
  return folders;
}

std::string ResolveBoardPath(const std::string& value, const std::vector<fs::path>& folders) {
  if (IsFile(value) || value.find('/') != std::string::npos) return value;
  for (const fs::path& folder : folders) {
    for (const fs::path& candidate : {folder / value, folder / (value + ".yaml")}) {
      if (IsFile(candidate)) return candidate.string();
    }
  }
  return "";
}

CLI::Validator ExistingBoardFile(const std::vector<fs::path>& folders) {
  return CLI::Validator(
      [folders](std::string& value) -> std::string {
        const std::string resolved = ResolveBoardPath(value, folders);
        if (resolved.empty()) return NotFound(value, folders);
        if (!IsFile(resolved)) return CLI::ExistingFile(resolved);
        value = resolved;
        return "";
      },
      "FILE|BOARD");
}

CLI::Validator ExistingCameraFile(const std::vector<fs::path>& folders) {
  return CLI::Validator(
      [folders](std::string& value) -> std::string {
        if (IsFile(value)) return "";
        const size_t hash = value.rfind('#');
        const std::string file = hash == std::string::npos ? value : value.substr(0, hash);
        const std::string block = hash == std::string::npos ? "" : value.substr(hash);
        const std::string resolved = ResolveBoardPath(file, folders);
        if (resolved.empty()) return NotFound(file, folders);
        if (!IsFile(resolved)) return CLI::ExistingFile(resolved);
        value = resolved + block;
        return "";
      },
      "FILE[#NAME]");
}

}  // namespace h4::cli
