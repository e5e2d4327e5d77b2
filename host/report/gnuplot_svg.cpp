// gnuplot as a subprocess producing inline SVG (see gnuplot_svg.h).
#include "host/report/gnuplot_svg.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>
#include <sys/wait.h>
#include <unistd.h>

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

}  // namespace

bool GnuplotAvailable() { return std::system("gnuplot --version > /dev/null 2>&1") == 0; }

std::string RenderSvg(const std::string& script, int width_px, int height_px) {
  const TempDir dir;
  const auto script_path = dir.path / "figure.gp";
  const auto svg_path = dir.path / "figure.svg";
  const auto log_path = dir.path / "gnuplot.log";
  {
    std::ofstream out(script_path);
    out << fmt::format(
        "set terminal svg size {},{} font 'DejaVu Sans,12' background rgb 'white'\n"
        "set output '{}'\n",
        width_px, height_px, svg_path.string());
    out << script << "\nunset output\n";
  }
  const std::string command =
      fmt::format("gnuplot '{}' > '{}' 2>&1", script_path.string(), log_path.string());
  const int status = std::system(command.c_str());
  if (status != 0) {
    const std::string log = ReadAll(log_path);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
      throw std::runtime_error(
          "gnuplot not found: the report's figures need it (Debian package gnuplot-nox; "
          "scripts/setup installs it)");
    }
    throw std::runtime_error("gnuplot failed drawing a report figure: " + log);
  }
  std::string svg = ReadAll(svg_path);
  const size_t start = svg.find("<svg");
  if (start == std::string::npos) {
    throw std::runtime_error("gnuplot wrote no SVG for a report figure: " + ReadAll(log_path));
  }
  return svg.substr(start);
}

}  // namespace h4::host
