// A printable page for a calibration board: the black rectangles of the pattern at exact
// scale, a white margin, and a caption with the board's dimensions and a 100 mm check
// bar. Page coordinates: m, origin at the top-left corner of the page, x right, y down.
// The SVG, PDF and PNG writers (board_print.h) all draw this one layout.
#pragma once

#include <string>
#include <vector>

#include "common/board/board_spec.h"

namespace h4::cam {

struct PrintRect {
  double x = 0, y = 0;  ///< top-left corner on the page, m
  double w = 0, h = 0;  ///< size, m
};

struct PrintText {
  double x = 0, y = 0;  ///< start of the baseline on the page, m
  double size = 0;      ///< font size (em height), m
  std::string text;     ///< ASCII only (PDF's standard Helvetica, OpenCV's Hershey fonts)
};

/// The page a board is laid out on: exactly the pattern, its margins and caption (kFit), an
/// ISO page (portrait, or landscape when only that holds it) with the board centred on it,
/// or the smallest of A4 and A3 that holds the board (kSmallestIso; the board's own size
/// when neither does), so that a printer prints it at 100 % without a custom page size.
enum class PaperSize { kFit, kA4, kA3, kSmallestIso };

struct BoardPrintOptions {
  double margin = 0.01;  ///< white border around the pattern, m (>= 0)
  PaperSize paper = PaperSize::kFit;
  /// Caption and 100 mm check bar below the pattern (off only for tests of the pattern).
  bool caption = true;

  bool IsValid(std::string* why) const;
};

struct BoardLayout {
  double width = 0, height = 0;         ///< page size, m
  double pattern_x = 0, pattern_y = 0;  ///< where board frame T's origin is on the page, m
  std::vector<PrintRect> black;         ///< the pattern (adjacent cells merged along rows)
  PrintRect scale_bar;                  ///< 100 mm long when captioned (w = 0 otherwise)
  std::vector<PrintText> texts;
};

/// The length of the check bar, m.
inline constexpr double kScaleBarLength = 0.1;

/// One-line description: "aprilgrid 6x6 tag36h11 (ids 0-35), tag 30.0 mm, spacing 7.5 mm".
std::string DescribeBoard(const BoardSpec& board);

/// Lays the board out; false with `error` set for an unsupported tag family, ids beyond
/// the family, or invalid options.
bool LayoutBoard(const BoardSpec& board, const BoardPrintOptions& options, BoardLayout* layout,
                 std::string* error);

}  // namespace h4::cam
