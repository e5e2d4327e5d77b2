// Calibration board descriptions (board YAML, formats.md): an AprilTag grid with
// Kalibr's keys, or an OpenCV chessboard. Board frame T: origin at the first
// corner, x along a row, y down a column, z into the board (away from the print).
#pragma once

#include <string>
#include <variant>

namespace h4 {

struct AprilGridSpec {
  std::string tag_family = "tag36h11";
  int cols = 6;             ///< tagCols
  int rows = 6;             ///< tagRows
  double tag_size = 0.03;   ///< tagSize: outer edge of the black border, m
  double tag_spacing = 0.25;///< tagSpacing: gap between tags / tagSize (unitless)
  int first_id = 0;         ///< firstId: id of the top-left tag; ids run row by row
};

struct CheckerboardSpec {
  int cols = 9;                 ///< targetCols: inner corners along a row
  int rows = 6;                 ///< targetRows: inner corners along a column
  double col_spacing = 0.025;   ///< colSpacingMeters, m
  double row_spacing = 0.025;   ///< rowSpacingMeters, m
};

using BoardSpec = std::variant<AprilGridSpec, CheckerboardSpec>;

}  // namespace h4
