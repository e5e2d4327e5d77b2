// `h4cam make-board --board B.yaml --out board.svg|png|pdf [--dpi 300] [--margin 0.01]
// [--paper auto|a4|a3|fit]`:
// a printable board at exact scale with its dimensions and a 100 mm check bar on it.
#pragma once

#include <iosfwd>
#include <string>

#include "firmware/board_print/board_layout.h"

namespace CLI {
class App;
}

namespace h4::cam {

struct MakeBoardArgs {
  std::string board_path;  ///< board YAML
  std::string out_path;    ///< .svg, .pdf or .png
  double dpi = 300;        ///< PNG only, dots per inch
  double margin = 0.01;    ///< white border around the pattern, m
  /// --paper: auto (the smallest of A4 and A3 that holds the board), a4, a3 or fit.
  PaperSize paper = PaperSize::kSmallestIso;
};

void DeclareMakeBoardCommand(CLI::App* command);

/// Writes the board file, reporting to `out`. Throws std::runtime_error (or
/// h4::FormatError for the board file) naming the file on failure.
void RunMakeBoard(const MakeBoardArgs& args, std::ostream& out);

}  // namespace h4::cam
