// Test helper: the board specifications the tests build, in one call rather than field by
// field.
#pragma once

#include "common/board/board_spec.h"

namespace h4 {

/// A chessboard of `cols` x `rows` inner corners, `col_spacing` and `row_spacing` (m) apart.
inline CheckerboardSpec Chessboard(int cols, int rows, double col_spacing, double row_spacing) {
  CheckerboardSpec board;
  board.cols = cols;
  board.rows = rows;
  board.col_spacing = col_spacing;
  board.row_spacing = row_spacing;
  return board;
}

}  // namespace h4
