// Printed board colours; see board_pattern.h.
#include "firmware/render/board_pattern.h"

#include <algorithm>
#include <cmath>

#include <apriltag/apriltag.h>
#include <fmt/format.h>

#include "firmware/detection/tag_family.h"

namespace h4::cam {

BoardPattern::BoardPattern(const BoardSpec& spec, double margin) : spec_(spec), model_(spec) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&spec_)) {
    margin_ = margin >= 0 ? margin : grid->tag_size;
    const TagFamilyPtr family = CreateTagFamily(grid->tag_family);
    if (!family) {
      error_ = "unsupported tag family '" + grid->tag_family + "'";
      return;
    }
    // Tag cells in print order (row from the top, then column); the layout decides which
    // id is printed where, and how wide the black border is.
    const int border_cells = grid->design().border_cells;
    for (int row = 0; row < grid->rows; ++row) {
      for (int col = 0; col < grid->cols; ++col) {
        const int id = model_.TagIdAt(row, col);
        tag_cells_.push_back(TagCells(*family, id, border_cells, &cells_));
        if (tag_cells_.back().empty()) {
          error_ = fmt::format("tag id {} is beyond family {} ({} codes)", id, grid->tag_family,
                               family->ncodes);
          return;
        }
      }
    }
    const double cell = grid->tag_size / cells_;
    for (int col = 0; col < grid->cols; ++col) {
      for (int k = 0; k <= cells_; ++k) xs_.push_back(model_.TagOrigin(0, col).x() + k * cell);
    }
    for (int row = 0; row < grid->rows; ++row) {
      for (int k = 0; k <= cells_; ++k) ys_.push_back(model_.TagOrigin(row, 0).y() + k * cell);
    }
  } else {
    const auto& board = std::get<CheckerboardSpec>(spec_);
    margin_ = margin >= 0 ? margin : std::max(board.col_spacing, board.row_spacing);
    for (int k = -1; k <= board.cols; ++k) xs_.push_back(k * board.col_spacing);
    for (int k = -1; k <= board.rows; ++k) ys_.push_back(k * board.row_spacing);
  }
  min_ = model_.pattern_min() - Eigen::Vector2d::Constant(margin_);
  max_ = model_.pattern_max() + Eigen::Vector2d::Constant(margin_);
  xs_.push_back(min_.x());
  xs_.push_back(max_.x());
  ys_.push_back(min_.y());
  ys_.push_back(max_.y());
  std::sort(xs_.begin(), xs_.end());
  std::sort(ys_.begin(), ys_.end());
}

BoardPattern::Colour BoardPattern::At(double x, double y) const {
  if (!(x >= min_.x() && x < max_.x() && y >= min_.y() && y < max_.y())) return kOff;
  return model_.is_aprilgrid() ? AprilGridAt(x, y) : CheckerAt(x, y);
}

BoardPattern::Colour BoardPattern::AprilGridAt(double x, double y) const {
  const auto& grid = std::get<AprilGridSpec>(spec_);
  const double pitch = grid.tag_size * (1.0 + grid.tag_spacing);
  const int col = static_cast<int>(std::floor(x / pitch));
  const int row = static_cast<int>(std::floor(y / pitch));
  const double lx = x - col * pitch, ly = y - row * pitch;
  // Right of and below each tag's pitch cell's tag square lies the gap crossing, where
  // Kalibr's layout prints a corner square (also left of / above the first row, col -1).
  const bool in_crossing = lx >= grid.tag_size && ly >= grid.tag_size;
  if (in_crossing && grid.design().corner_squares && col >= -1 && col < grid.cols && row >= -1 &&
      row < grid.rows) {
    return kBlack;
  }
  if (col < 0 || col >= grid.cols || row < 0 || row >= grid.rows) return kWhite;
  if (lx >= grid.tag_size || ly >= grid.tag_size) return kWhite;
  const double cell = grid.tag_size / cells_;
  const int cx = std::clamp(static_cast<int>(lx / cell), 0, cells_ - 1);
  const int cy = std::clamp(static_cast<int>(ly / cell), 0, cells_ - 1);
  const auto& cells = tag_cells_[static_cast<size_t>(row * grid.cols + col)];
  return cells[static_cast<size_t>(cy * cells_ + cx)] ? kWhite : kBlack;
}

BoardPattern::Colour BoardPattern::CheckerAt(double x, double y) const {
  // Square (i, j), i = 0 for the column left of the first inner corner; the top-left
  // square (0, 0) is black, as OpenCV's pattern generator prints it.
  const auto& board = std::get<CheckerboardSpec>(spec_);
  const int i = static_cast<int>(std::floor(x / board.col_spacing)) + 1;
  const int j = static_cast<int>(std::floor(y / board.row_spacing)) + 1;
  if (i < 0 || i > board.cols || j < 0 || j > board.rows) return kWhite;
  return ((i + j) % 2 == 0) ? kBlack : kWhite;
}

bool BoardPattern::MayChange(double x0, double y0, double x1, double y1) const {
  // Entirely off the printed board: background. Across the board's edge: changes.
  if (x1 < min_.x() || x0 >= max_.x() || y1 < min_.y() || y0 >= max_.y()) return false;
  if (x0 < min_.x() || x1 >= max_.x() || y0 < min_.y() || y1 >= max_.y()) return true;
  if (model_.is_aprilgrid()) return AprilGridMayChange(x0, y0, x1, y1);
  const auto crosses = [](const std::vector<double>& v, double a, double b) {
    const auto it = std::lower_bound(v.begin(), v.end(), a);
    return it != v.end() && *it <= b;
  };
  return crosses(xs_, x0, x1) || crosses(ys_, y0, y1);
}

bool BoardPattern::AprilGridMayChange(double x0, double y0, double x1, double y1) const {
  // Tag cell boundaries only matter inside a tag; the white gaps between tags are uniform.
  const auto& grid = std::get<AprilGridSpec>(spec_);
  const double pitch = grid.tag_size * (1.0 + grid.tag_spacing);
  const int col = static_cast<int>(std::floor(x0 / pitch));
  const int row = static_cast<int>(std::floor(y0 / pitch));
  if (col != static_cast<int>(std::floor(x1 / pitch)) ||
      row != static_cast<int>(std::floor(y1 / pitch))) {
    return true;
  }
  const double lx0 = x0 - col * pitch, lx1 = x1 - col * pitch;
  const double ly0 = y0 - row * pitch, ly1 = y1 - row * pitch;
  const double s = grid.tag_size;
  // Corner squares: a box across the square's sides (x = s or y = s in the gap) changes.
  if (grid.design().corner_squares && ((lx0 < s) != (lx1 < s) || (ly0 < s) != (ly1 < s))) {
    return true;
  }
  if (col < 0 || col >= grid.cols || row < 0 || row >= grid.rows) return false;  // margin
  if (lx0 >= s || ly0 >= s) return false;  // in the gap right of / below the tag
  if (lx1 >= s || ly1 >= s) return true;   // across the tag's outer edge
  const double cell = s / cells_;
  const int cx0 = static_cast<int>(lx0 / cell),
            cx1 = std::min(static_cast<int>(lx1 / cell), cells_ - 1);
  const int cy0 = static_cast<int>(ly0 / cell),
            cy1 = std::min(static_cast<int>(ly1 / cell), cells_ - 1);
  const auto& cells = tag_cells_[static_cast<size_t>(row * grid.cols + col)];
  const bool first = cells[static_cast<size_t>(cy0 * cells_ + cx0)];
  for (int cy = cy0; cy <= cy1; ++cy) {
    for (int cx = cx0; cx <= cx1; ++cx) {
      if (cells[static_cast<size_t>(cy * cells_ + cx)] != first) return true;
    }
  }
  return false;
}

}  // namespace h4::cam
