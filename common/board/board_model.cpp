// Board corner positions; see board_model.h.
#include "common/board/board_model.h"

#include <fmt/format.h>

namespace h4 {

BoardModel::BoardModel(const BoardSpec& spec) : spec_(spec) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&spec_)) {
    BuildAprilGrid(*grid);
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

void BoardModel::BuildAprilGrid(const AprilGridSpec& grid) {
  const double s = grid.tag_size;
  for (int index = 0; index < grid.rows * grid.cols; ++index) {
    const Eigen::Vector2i row_col = TagRowCol(index);
    const Eigen::Vector2d o = TagOrigin(row_col.x(), row_col.y());
    corners_.emplace_back(o.x(), o.y() + s, 0.0);      // k = 0 bottom-left
    corners_.emplace_back(o.x() + s, o.y() + s, 0.0);  // k = 1 bottom-right
    corners_.emplace_back(o.x() + s, o.y(), 0.0);      // k = 2 top-right
    corners_.emplace_back(o.x(), o.y(), 0.0);          // k = 3 top-left
  }
  if (grid.rows <= 0 || grid.cols <= 0) return;
  pattern_min_ = Eigen::Vector2d::Zero();
  pattern_max_ = TagOrigin(grid.rows - 1, grid.cols - 1) + Eigen::Vector2d(s, s);
  if (!grid.design().corner_squares) return;
  // One square at each crossing of the gaps, and along the outer edges: it spans
  // [x0 - g, x0] x [y0 - g, y0] at every tag-corner position (x0, y0) of the pitch grid.
  corner_square_size_ = grid.tag_spacing * s;
  const double pitch = s * (1.0 + grid.tag_spacing);
  for (int row = 0; row <= grid.rows; ++row) {
    for (int col = 0; col <= grid.cols; ++col) {
      corner_squares_.emplace_back(col * pitch - corner_square_size_,
                                   row * pitch - corner_square_size_);
    }
  }
  pattern_min_ -= Eigen::Vector2d::Constant(corner_square_size_);
  pattern_max_ += Eigen::Vector2d::Constant(corner_square_size_);
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

std::string BoardModel::CornerTagProblem(int tag_id, int corner_id) const {
  if (corner_id < 0 || corner_id >= corner_count()) {
    return fmt::format("corner {} is not on the board ({} corners)", corner_id, corner_count());
  }
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr) {
    if (tag_id == -1) return "";
    return fmt::format("tag_id {} on a chessboard, whose corners carry tag_id -1", tag_id);
  }
  const int expected = grid->first_id + corner_id / 4;
  if (tag_id == expected) return "";
  if (TagCornerId(tag_id, 0) < 0) {
    return fmt::format("tag_id {} is not on the board (tags {}..{}); corner {} is tag {}'s",
                       tag_id, grid->first_id, grid->first_id + grid->rows * grid->cols - 1,
                       corner_id, expected);
  }
  return fmt::format("corner {} is a corner of tag {}, not of tag_id {}", corner_id, expected,
                     tag_id);
}

Eigen::Vector2d BoardModel::TagOrigin(int row, int col) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr) return Eigen::Vector2d::Zero();
  const double pitch = grid->tag_size * (1.0 + grid->tag_spacing);
  return {col * pitch, row * pitch};
}

Eigen::Vector2i BoardModel::TagRowCol(int tag_index) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr || grid->cols <= 0) return Eigen::Vector2i::Zero();
  const int row_from_first = tag_index / grid->cols;
  const int row = grid->design().ids_from_bottom ? grid->rows - 1 - row_from_first : row_from_first;
  return {row, tag_index % grid->cols};
}

int BoardModel::TagIdAt(int row, int col) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr) return -1;
  const int row_from_first = grid->design().ids_from_bottom ? grid->rows - 1 - row : row;
  return grid->first_id + row_from_first * grid->cols + col;
}

int BoardModel::KalibrPointIndex(int corner_id) const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr || grid->layout != AprilGridLayout::kKalibr || corner_id < 0 ||
      corner_id >= corner_count()) {
    return -1;
  }
  // Kalibr's point grid has 2 tagCols columns; tag i's bottom-left point is at row
  // 2 (i / tagCols), column 2 (i % tagCols), its corners k = 0..3 at (+0, +0), (+0, +1),
  // (+1, +1), (+1, +0) (row, column) from there.
  const int tag_index = corner_id / 4, k = corner_id % 4;
  const int point_cols = 2 * grid->cols;
  const int base = (tag_index / grid->cols) * 2 * point_cols + (tag_index % grid->cols) * 2;
  const int offsets[4] = {0, 1, point_cols + 1, point_cols};
  return base + offsets[k];
}

RigidTransform BoardModel::KalibrTargetPose() const {
  const auto* grid = std::get_if<AprilGridSpec>(&spec_);
  if (grid == nullptr) return {};
  const double grid_height =
      grid->rows * grid->tag_size + (grid->rows - 1) * grid->tag_spacing * grid->tag_size;
  return {Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal().toDenseMatrix(),
          Eigen::Vector3d(0.0, grid_height, 0.0)};
}

}  // namespace h4
