// `h4cam make-board --board B.yaml --out board.svg|png|pdf [--dpi 300] [--margin 0.01]`:
// a printable board at exact scale with its dimensions and a 100 mm check bar on it.
#pragma once

#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace h4::cam {

struct MakeBoardArgs {
  std::string board_path;  ///< board YAML
  std::string out_path;    ///< .svg, .pdf or .png
  double dpi = 300;        ///< PNG only, dots per inch
  double margin = 0.01;    ///< white border around the pattern, m
};

void DeclareMakeBoardCommand(CLI::App* command);

/// Writes the board file, reporting to `out`. Throws std::runtime_error (or
/// h4::FormatError for the board file) naming the file on failure.
void RunMakeBoard(const MakeBoardArgs& args, std::ostream& out);

}  // namespace h4::cam
