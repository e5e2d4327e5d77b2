// Board corner positions; see board_model.h.
#include "common/board/board_model.h"

namespace h4 {

BoardModel::BoardModel(const BoardSpec& spec) : spec_(spec) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&spec_)) {
    const double s = grid->tag_size;
    for (int row = 0; row < grid->rows; ++row) {
      for (int col = 0; col < grid->cols; ++col) {
        const Eigen::Vector2d o = TagOrigin(row, col);
        corners_.emplace_back(o.x(), o.y() + s, 0.0);      // k = 0 bottom-left
        corners_.emplace_back(o.x() + s, o.y() + s, 0.0);  // k = 1 bottom-right
        corners_.emplace_back(o.x() + s, o.y(), 0.0);      // k = 2 top-right
        corners_.emplace_back(o.x(), o.y(), 0.0);          // k = 3 top-left
      }
    }
    pattern_min_ = Eigen::Vector2d::Zero();
    if (grid->rows > 0 && grid->cols > 0) {
      pattern_max_ = TagOrigin(grid->rows - 1, grid->cols - 1) + Eigen::Vector2d(s, s);
    }
  } else {
    const auto& board = std::get<CheckerboardSpec>(spec_);
    for (int row = 0; row < board.rows; ++row) {
      for (int col = 0; col < board.cols; ++col) {
        corners_.emplace_back(col * board.col_spacing, row * board.row_spacing, 0.0);
      }
    }
    // The squares extend one square beyond the outer inner corners.
    pattern_min_ = Eigen::Vector2d(-board.col_spacing, -board.row_spacing);
    pattern_max_ = Eigen::Vector2d(board.cols * board.col_spacing, board.rows * board.row_spacing);
  }
}

std::optional<Eigen::Vector3d> BoardModel::Corner(int corner_id) const {
  if (corner_id < 0 || corner_id >= corner_count()) return std::nullopt;
  return corners_[static_cast<size_t>(corner_id)];
}

int BoardModel::TagCornerId(int tag_id, int k) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr || k < 0 || k > 3) return -1;
  const int index = tag_id - grid->first_id;
  if (index < 0 || index >= grid->rows * grid->cols) return -1;
  return 4 * index + k;
}

Eigen::Vector2d BoardModel::TagOrigin(int row, int col) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr) return Eigen::Vector2d::Zero();
  const double pitch = grid->tag_size * (1.0 + grid->tag_spacing);
  return {col * pitch, row * pitch};
}

}  // namespace h4
