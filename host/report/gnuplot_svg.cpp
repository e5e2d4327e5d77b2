// gnuplot as a subprocess producing inline SVG (see gnuplot_svg.h).
#include "host/report/gnuplot_svg.h"

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <spdlog/fmt/fmt.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace h4::host {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A fresh temporary folder, removed when this goes out of scope.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "h4cal-plot-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder");
    path = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

constexpr int kNotFound = -1;

/// Runs gnuplot with `arguments` (an argument vector: no shell, so no path needs quoting),
/// its stdout and stderr into the given files. Returns its wait status, or kNotFound.
int RunGnuplot(const std::vector<std::string>& arguments, const std::string& stdout_path,
               const std::string& stderr_path) {
  std::vector<char*> argv;
  std::string program = "gnuplot";
  argv.push_back(program.data());
  std::vector<std::string> copies = arguments;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, stdout_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&files, STDERR_FILENO, stderr_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned == ENOENT) return kNotFound;
  if (spawned != 0) throw std::runtime_error(fmt::format("cannot run gnuplot (errno {})", spawned));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace

bool GnuplotAvailable() { return RunGnuplot({"--version"}, "/dev/null", "/dev/null") == 0; }

std::string RenderSvg(const std::string& script, int width_px, int height_px) {
  const TempDir dir;
  const auto script_path = dir.path / "figure.gp";
  const auto svg_path = dir.path / "figure.svg";
  const auto log_path = dir.path / "gnuplot.log";
  {
    // No `set output`: the SVG goes to gnuplot's stdout, which RunGnuplot sends to svg_path.
    std::ofstream out(script_path);
    out << fmt::format("set terminal svg size {},{} font 'DejaVu Sans,12' background rgb 'white'\n",
                       width_px, height_px);
    out << script << "\n";
  }
  const int status = RunGnuplot({script_path.string()}, svg_path.string(), log_path.string());
  if (status == kNotFound) {
    throw std::runtime_error(
        "gnuplot not found: the report's figures need it (Debian package gnuplot-nox; "
        "scripts/setup installs it)");
  }
  if (status != 0) {
    throw std::runtime_error("gnuplot failed drawing a report figure: " + ReadAll(log_path));
  }
  std::string svg = ReadAll(svg_path);
  const size_t start = svg.find("<svg");
  if (start == std::string::npos) {
    throw std::runtime_error("gnuplot wrote no SVG for a report figure: " + ReadAll(log_path));
  }
  return svg.substr(start);
}

}  // namespace h4::host
