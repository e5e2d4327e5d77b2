// Tests for common/board/board_model: corner positions of AprilTag grids and chessboards
// by known values (formats.md's board frame T).
#include "common/board/board_model.h"

#include <gtest/gtest.h>

namespace h4 {
namespace {

TEST(BoardModelTest, AprilGridCornersFollowTagLayoutAndAprilTagOrder) {
  AprilGridSpec grid;
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

TEST(BoardModelTest, ChessboardCornersAreRowMajorFromFirstInnerCorner) {
  CheckerboardSpec spec;
  spec.cols = 9;
  spec.rows = 6;
  spec.col_spacing = 0.025;
  spec.row_spacing = 0.02;
  const BoardModel board(spec);
  ASSERT_EQ(board.corner_count(), 54);
  EXPECT_EQ(board.corners()[0], Eigen::Vector3d::Zero());
  EXPECT_NEAR((board.corners()[1] - Eigen::Vector3d(0.025, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((board.corners()[9 * 2 + 3] - Eigen::Vector3d(0.075, 0.04, 0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(board.TagCornerId(0, 0), -1);
}

}  // namespace
}  // namespace h4
