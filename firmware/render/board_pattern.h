// The printed face of a calibration board as a function of position in the board plane
// (frame T, z = 0): black, white, or off the board. Used by the renderer, which also asks
// whether a small box may straddle a colour boundary (then it supersamples the pixel).
#pragma once

#include <string>
#include <vector>

#include "common/board/board_model.h"

namespace h4::cam {

class BoardPattern {
 public:
  enum Colour : int { kOff = -1, kBlack = 0, kWhite = 1 };

  /// `margin` (m): white border printed around the pattern; negative = one tag size (one
  /// square for a chessboard). For AprilTag grids the family must be supported
  /// (tag_family.h); otherwise ok() is false and error() says why.
  BoardPattern(const BoardSpec& spec, double margin);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  /// Printed extent (pattern plus margin) in the board plane, m.
  Eigen::Vector2d extent_min() const { return min_; }
  Eigen::Vector2d extent_max() const { return max_; }
  /// Colour at (x, y) in T, m.
  Colour At(double x, double y) const;
  /// False only when the colour is certainly uniform over the box [x0, x1] x [y0, y1]
  /// (inside one tag cell or cells of one colour, in a gap, or off the board).
  bool MayChange(double x0, double y0, double x1, double y1) const;

 private:
  Colour AprilGridAt(double x, double y) const;
  Colour CheckerAt(double x, double y) const;
  bool AprilGridMayChange(double x0, double y0, double x1, double y1) const;

  BoardSpec spec_;
  BoardModel model_;
  double margin_ = 0;
  Eigen::Vector2d min_, max_;                 // printed extent incl. margin
  std::vector<double> xs_, ys_;               // sorted boundary coordinates
  int cells_ = 0;                             // tag width in cells
  std::vector<std::vector<bool>> tag_cells_;  // per tag index, row-major, true = white
  std::string error_;
};

}  // namespace h4::cam
