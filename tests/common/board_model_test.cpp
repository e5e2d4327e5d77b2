// Tests for common/board/board_model: corner positions of AprilTag grids (h4cam's legacy
// layout and Kalibr's) and chessboards by known values (board frame T of
// common/formats/README.md), and Kalibr's own point list through X_TK.
#include "common/board/board_model.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "tests/support/board_specs.h"

namespace h4 {
namespace {

TEST(BoardModelTest, LegacyAprilGridCornersFollowTagLayoutAndAprilTagOrder) {
  AprilGridSpec grid;
  grid.layout = AprilGridLayout::kH4Legacy;
  grid.cols = 3;
  grid.rows = 2;
  grid.tag_size = 0.04;
  grid.tag_spacing = 0.25;  // pitch 0.05 m
  grid.first_id = 10;
  const BoardModel board(grid);
  ASSERT_EQ(board.corner_count(), 24);
  // Tag 10: top-left tag, origin at (0, 0); corner order bottom-left, bottom-right,
  // top-right, top-left with y down.
  EXPECT_EQ(board.corners()[0], Eigen::Vector3d(0.0, 0.04, 0.0));
  EXPECT_EQ(board.corners()[1], Eigen::Vector3d(0.04, 0.04, 0.0));
  EXPECT_EQ(board.corners()[2], Eigen::Vector3d(0.04, 0.0, 0.0));
  EXPECT_EQ(board.corners()[3], Eigen::Vector3d(0.0, 0.0, 0.0));
  // Tag 15: row 1, column 2: origin (0.10, 0.05).
  const int id = board.TagCornerId(15, 1);
  ASSERT_EQ(id, 21);
  EXPECT_NEAR((board.corners()[21] - Eigen::Vector3d(0.14, 0.09, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.pattern_max() - Eigen::Vector2d(0.14, 0.09)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(board.corner_squares().empty());
  EXPECT_EQ(board.KalibrPointIndex(0), -1);
}

AprilGridSpec KalibrGrid() {
  AprilGridSpec grid;  // a plain Kalibr YAML: Kalibr's layout
  grid.cols = 3;
  grid.rows = 2;
  grid.tag_size = 0.04;
  grid.tag_spacing = 0.25;  // pitch 0.05 m, gaps 0.01 m
  return grid;
}

TEST(BoardModelTest, KalibrIdsStartAtTheBottomLeftTagAndRunRightThenUp) {
  const BoardModel board(KalibrGrid());
  // Tag 0 is printed in the bottom row (row 1 from the top), first column.
  EXPECT_EQ(board.TagRowCol(0), Eigen::Vector2i(1, 0));
  EXPECT_EQ(board.TagRowCol(2), Eigen::Vector2i(1, 2));
  EXPECT_EQ(board.TagRowCol(3), Eigen::Vector2i(0, 0));
  EXPECT_EQ(board.TagIdAt(0, 0), 3);
  EXPECT_EQ(board.TagIdAt(1, 1), 1);
  // Tag 0's corners: bottom-left (0, 0.09), ..., top-left (0, 0.05) in T (y down).
  EXPECT_NEAR((board.corners()[0] - Eigen::Vector3d(0.0, 0.09, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.corners()[2] - Eigen::Vector3d(0.04, 0.05, 0.0)).norm(), 0.0, 1e-15);
  // Tag 5 (top-right): top-left corner at (0.10, 0).
  EXPECT_NEAR((board.corners()[board.TagCornerId(5, 3)] - Eigen::Vector3d(0.10, 0.0, 0.0)).norm(),
              0.0, 1e-15);
}

TEST(BoardModelTest, KalibrCornerSquaresSitAtEveryTagCornerAndWidenThePattern) {
  const BoardModel board(KalibrGrid());
  ASSERT_EQ(board.corner_squares().size(), 12u);  // (3 + 1) x (2 + 1) gap crossings
  EXPECT_NEAR(board.corner_square_size(), 0.01, 1e-15);
  // The first square touches tag (0, 0)'s top-left corner from outside; the last one the
  // bottom-right corner of the bottom-right tag.
  EXPECT_NEAR((board.corner_squares().front() - Eigen::Vector2d(-0.01, -0.01)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.corner_squares().back() - Eigen::Vector2d(0.14, 0.09)).norm(), 0.0, 1e-15);
  // Every tag corner is the shared vertex of one corner square.
  for (const Eigen::Vector3d& p_TQ : board.corners()) {
    int touching = 0;
    for (const Eigen::Vector2d& square : board.corner_squares()) {
      const Eigen::Vector2d far = square + Eigen::Vector2d::Constant(0.01);
      for (const Eigen::Vector2d& vertex : {square, far, Eigen::Vector2d(square.x(), far.y()),
                                            Eigen::Vector2d(far.x(), square.y())}) {
        if ((vertex - p_TQ.head<2>()).norm() < 1e-12) ++touching;
      }
    }
    EXPECT_EQ(touching, 1) << p_TQ.transpose();
  }
  EXPECT_NEAR((board.pattern_min() - Eigen::Vector2d(-0.01, -0.01)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.pattern_max() - Eigen::Vector2d(0.15, 0.10)).norm(), 0.0, 1e-15);
}

// Kalibr's GridCalibrationTargetAprilgrid::createGridPoints: point (r, c) of the
// (2 tagRows) x (2 tagCols) grid, in Kalibr's target frame K (y up the print).
Eigen::Vector3d KalibrPoint(const AprilGridSpec& grid, int index) {
  const int point_cols = 2 * grid.cols;
  const int r = index / point_cols, c = index % point_cols;
  const double pitch = (1 + grid.tag_spacing) * grid.tag_size;
  return {(c / 2) * pitch + (c % 2) * grid.tag_size, (r / 2) * pitch + (r % 2) * grid.tag_size,
          0.0};
}

TEST(BoardModelTest, KalibrCornersAreKalibrsTargetPointsSeenFromT) {
  const AprilGridSpec grid = KalibrGrid();
  const BoardModel board(grid);
  const RigidTransform X_TK = board.KalibrTargetPose();
  std::vector<int> seen(24, 0);
  for (int id = 0; id < board.corner_count(); ++id) {
    const int index = board.KalibrPointIndex(id);
    ASSERT_GE(index, 0);
    ASSERT_LT(index, 24);
    ++seen[static_cast<size_t>(index)];
    const Eigen::Vector3d p_TQ = X_TK * KalibrPoint(grid, index);
    EXPECT_NEAR((p_TQ - board.corners()[static_cast<size_t>(id)]).norm(), 0.0, 1e-15) << id;
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 24);
  // Kalibr's order for tag 0 (its comment): 0 bottom-left, 1 bottom-right, then the
  // top row of the point grid: 7 top-right, 6 top-left.
  EXPECT_EQ(board.KalibrPointIndex(1), 1);
  EXPECT_EQ(board.KalibrPointIndex(2), 7);
  EXPECT_EQ(board.KalibrPointIndex(3), 6);
  EXPECT_EQ(board.KalibrPointIndex(4 * 3), 12);  // tag 3: bottom-left, third point row
  // z of K points out of the print, z of T into it.
  EXPECT_NEAR((X_TK.rotation() * Eigen::Vector3d::UnitZ() + Eigen::Vector3d::UnitZ()).norm(), 0.0,
              1e-15);
}

TEST(BoardModelTest, TagIdsOffTheBoardHaveNoCorners) {
  AprilGridSpec grid;
  grid.first_id = 5;
  const BoardModel board(grid);
  EXPECT_EQ(board.TagCornerId(4, 0), -1);
  EXPECT_EQ(board.TagCornerId(5 + 36, 0), -1);
  EXPECT_EQ(board.TagCornerId(5, 4), -1);
  EXPECT_FALSE(board.Corner(-1).has_value());
  EXPECT_FALSE(board.Corner(144).has_value());
}

// Issue 42 point 15: a corners CSV's tag_id was never checked: 99 on a 36-tag board, 7 for
// corner 4 (tag 1's), a tag id on a chessboard all fitted. The board says which pairs are its.
TEST(BoardModelTest, ACornerRowsTagIdMustBeItsCornersTag) {
  AprilGridSpec grid;
  grid.first_id = 5;
  const BoardModel board(grid);
  EXPECT_EQ(board.CornerTagProblem(5, 0), "");
  EXPECT_EQ(board.CornerTagProblem(6, 4), "");
  EXPECT_EQ(board.CornerTagProblem(5 + 35, 143), "");
  EXPECT_EQ(board.CornerTagProblem(99, 4),
            "tag_id 99 is not on the board (tags 5..40); corner 4 is tag 6's");
  EXPECT_EQ(board.CornerTagProblem(7, 4), "corner 4 is a corner of tag 6, not of tag_id 7");
  EXPECT_EQ(board.CornerTagProblem(-1, 4), "tag_id -1 is not on the board (tags 5..40); corner 4 "
                                           "is tag 6's");
  EXPECT_EQ(board.CornerTagProblem(5, 144), "corner 144 is not on the board (144 corners)");
  const BoardModel chessboard(Chessboard(9, 6, 0.025, 0.02));
  EXPECT_EQ(chessboard.CornerTagProblem(-1, 53), "");
  EXPECT_EQ(chessboard.CornerTagProblem(0, 3),
            "tag_id 0 on a chessboard, whose corners carry tag_id -1");
  EXPECT_EQ(chessboard.CornerTagProblem(-1, 54), "corner 54 is not on the board (54 corners)");
}

TEST(BoardModelTest, ChessboardCornersAreRowMajorFromFirstInnerCorner) {
  const CheckerboardSpec spec = Chessboard(9, 6, 0.025, 0.02);
  const BoardModel board(spec);
  ASSERT_EQ(board.corner_count(), 54);
  EXPECT_EQ(board.corners()[0], Eigen::Vector3d::Zero());
  EXPECT_NEAR((board.corners()[1] - Eigen::Vector3d(0.025, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.corners()[9 * 2 + 3] - Eigen::Vector3d(0.075, 0.04, 0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(board.TagCornerId(0, 0), -1);
}

}  // namespace
}  // namespace h4
