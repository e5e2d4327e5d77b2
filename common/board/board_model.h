// Corner positions p_TQ of a calibration board in its frame T (formats.md: origin at the
// outer top-left corner of tag firstId / the first inner chessboard corner, x right along
// a row, y down a column, z into the board; the printed face is the plane z = 0).
//
// Corner ids: AprilTag grid: 4 * (tag_id - firstId) + k, where k follows libapriltag's
// corner order seen on the print with y down: k = 0 bottom-left (x0, y0 + s),
// 1 bottom-right (x0 + s, y0 + s), 2 top-right (x0 + s, y0), 3 top-left (x0, y0), with
// (x0, y0) the outer top-left corner of the tag and s its size.
// Chessboard: row * targetCols + col over the inner corners, row-major.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_spec.h"

namespace h4 {

class BoardModel {
 public:
  explicit BoardModel(const BoardSpec& spec);

  const BoardSpec& spec() const { return spec_; }
  bool is_aprilgrid() const { return std::holds_alternative<AprilGridSpec>(spec_); }
  /// Number of corner ids (all corners of all tags, or all inner chessboard corners).
  int corner_count() const { return static_cast<int>(corners_.size()); }
  /// p_TQ of every corner, indexed by corner id, m.
  const std::vector<Eigen::Vector3d>& corners() const { return corners_; }
  /// p_TQ of one corner, nullopt for an id outside [0, corner_count()).
  std::optional<Eigen::Vector3d> Corner(int corner_id) const;

  /// AprilTag grid: corner id of corner k (0..3) of tag `tag_id`, or -1 when the tag id
  /// is not on this board (or the board is a chessboard).
  int TagCornerId(int tag_id, int k) const;
  /// AprilTag grid: outer top-left corner (x0, y0) of the tag in row `row`, column
  /// `col`, m. Tags are laid out with pitch tagSize * (1 + tagSpacing).
  Eigen::Vector2d TagOrigin(int row, int col) const;

  /// Extent of the pattern (black features) in the board plane: min and max (x, y), m.
  Eigen::Vector2d pattern_min() const { return pattern_min_; }
  Eigen::Vector2d pattern_max() const { return pattern_max_; }

 private:
  BoardSpec spec_;
  std::vector<Eigen::Vector3d> corners_;
  Eigen::Vector2d pattern_min_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d pattern_max_ = Eigen::Vector2d::Zero();
};

}  // namespace h4
