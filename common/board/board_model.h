// Corner positions p_TQ of a calibration board in its frame T
// (common/formats/README.md#board-yaml---board: origin at the outer top-left corner of the top-left
// tag as printed / the first inner chessboard corner, x right along a row, y down a column, z into
// the board; the printed face is the plane z = 0).
//
// Corner ids: AprilTag grid: 4 * (tag_id - firstId) + k, where k follows libapriltag's
// corner order seen on the print with y down: k = 0 bottom-left (x0, y0 + s),
// 1 bottom-right (x0 + s, y0 + s), 2 top-right (x0 + s, y0), 3 top-left (x0, y0), with
// (x0, y0) the outer top-left corner of the tag and s its size. Kalibr's detector reports
// its tag corners in the same order, so for a Kalibr board (firstId 0) corner id
// 4 * tag_id + k is Kalibr's corner k of tag tag_id (KalibrPointIndex gives its index in
// Kalibr's target point list).
// Chessboard: row * targetCols + col over the inner corners, row-major.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_spec.h"
#include "common/geometry/rigid_transform.h"

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
  /// Empty when a corners CSV row's (tag_id, corner) names a corner of this board: on an
  /// AprilTag grid corner id 4 * (tag_id - firstId) + k of a tag on the board, on a
  /// chessboard a corner id in range with tag_id -1 (common/formats/README.md#board-corners-csv);
  /// else why ("tag_id 99 is not on the board (tags 0..35); corner 4 is tag 1's").
  std::string CornerTagProblem(int tag_id, int corner_id) const;
  /// AprilTag grid: outer top-left corner (x0, y0) of the tag in row `row` (counted from
  /// the top of the print), column `col`, m. Tags are laid out with pitch
  /// tagSize * (1 + tagSpacing).
  Eigen::Vector2d TagOrigin(int row, int col) const;
  /// AprilTag grid: row (from the top) and column of the tag with index
  /// tag_id - firstId; the layout decides whether ids start at the top or the bottom.
  Eigen::Vector2i TagRowCol(int tag_index) const;
  /// AprilTag grid: id of the tag printed in row `row` (from the top), column `col`.
  int TagIdAt(int row, int col) const;

  /// Kalibr layout: top-left corners (x, y) of the black squares at the tag corners, m;
  /// each is a square of side corner_square_size(). Empty for other layouts.
  const std::vector<Eigen::Vector2d>& corner_squares() const { return corner_squares_; }
  double corner_square_size() const { return corner_square_size_; }

  /// Kalibr layout: index of corner `corner_id` in the point list of Kalibr's
  /// GridCalibrationTargetAprilgrid (a (2 tagRows) x (2 tagCols) grid, row-major from the
  /// bottom-left corner of tag 0), or -1 for an id off the board or another layout.
  int KalibrPointIndex(int corner_id) const;
  /// Kalibr layout: X_TK, the pose of Kalibr's target frame K in T. K has its origin at
  /// the outer bottom-left corner of the bottom-left tag, x right, y up the print, z out of
  /// the print; so R_TK = diag(1, -1, -1), p_TK = (0, H, 0) with H the height of the tag
  /// grid (rows tags and rows - 1 gaps).
  RigidTransform KalibrTargetPose() const;

  /// Extent of the pattern (black features) in the board plane: min and max (x, y), m.
  Eigen::Vector2d pattern_min() const { return pattern_min_; }
  Eigen::Vector2d pattern_max() const { return pattern_max_; }

 private:
  void BuildAprilGrid(const AprilGridSpec& grid);

  BoardSpec spec_;
  std::vector<Eigen::Vector3d> corners_;
  std::vector<Eigen::Vector2d> corner_squares_;
  double corner_square_size_ = 0;
  Eigen::Vector2d pattern_min_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d pattern_max_ = Eigen::Vector2d::Zero();
};

}  // namespace h4
