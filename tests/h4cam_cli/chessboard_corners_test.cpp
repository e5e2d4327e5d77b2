// Chessboard corners (firmware/detection/chessboard_corners.h): OpenCV's classic detector
// is given at most kClassicDetectorMaxPixels, so a board file whose corner count the image
// does not show is refused after a bounded search (it searched a 1024 x 768 view for 11 s,
// a 2028 x 1520 one for 74 s), and the corners it finds on the reduced copy land on the
// full-size corners once refined. The work is counted in pixels, not timed.
#include "firmware/detection/chessboard_corners.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "firmware/calibration/board_views.h"
#include "firmware/render/board_renderer.h"
#include "firmware/render/paper_scenes.h"
#include "tests/support/board_specs.h"

namespace h4::cam {
namespace {

CheckerboardSpec ChessboardOf(int cols, int rows) { return Chessboard(cols, rows, 0.02, 0.02); }

RigidTransform ChessboardPose() {
  const Eigen::Matrix3d R_CT = So3Exp(Eigen::Vector3d(0.2, -0.1, 0.1));
  const Eigen::Vector3d p_TCentre(0.08, 0.05, 0);
  return RigidTransform(R_CT, Eigen::Vector3d(0.0, 0.0, 0.5) - R_CT * p_TCentre);
}

// A 9 x 6 board (inner corners) seen by the paper's 1024 x 768 camera, without noise: the
// classic detector's search over noise quads costs seconds even at VGA size (5-6 s on the
// noisy rendering, 85 s at full size), which a unit test need not spend.
cv::Mat NineBySixChessboardView() {
  const BoardRenderer renderer(ChessboardOf(9, 6), scenes::PaperCamera(), RenderOptions{});
  EXPECT_TRUE(renderer.ok()) << renderer.error();
  cv::Mat view8;
  renderer.RenderClean(ChessboardPose()).convertTo(view8, CV_8U);
  return view8;
}

TEST(ChessboardCornersTest, AMismatchedCornerCountIsRefusedAfterABoundedSearch) {
  const cv::Mat view = NineBySixChessboardView();
  ASSERT_GT(int64_t{view.cols} * view.rows, kClassicDetectorMaxPixels);
  cv::Mat view32;
  view.convertTo(view32, CV_32F);
  for (const CheckerboardSpec& wrong : {ChessboardOf(8, 6), ChessboardOf(10, 7)}) {
    ChessboardWork work;
    std::vector<Eigen::Vector2d> uv;
    EXPECT_FALSE(FindChessboardCorners(view, view32, wrong, 5, &uv, &work));
    EXPECT_GT(work.classic_pixels, 0) << "the classic detector is the fallback";
    EXPECT_LE(work.classic_pixels, kClassicDetectorMaxPixels) << wrong.cols << "x" << wrong.rows;

    const BoardViewFinder finder(wrong);  // calibrate-intrinsics
    std::string why;
    EXPECT_FALSE(finder.Find(view, "view.png", &why).has_value());
    EXPECT_NE(why.find(fmt::format("{}x{}", wrong.cols, wrong.rows)), std::string::npos) << why;
    EXPECT_LE(finder.chessboard_work().classic_pixels, kClassicDetectorMaxPixels);
  }
}

TEST(ChessboardCornersTest, CornersFoundOnTheReducedCopyLandOnTheFullSizeCorners) {
  const cv::Mat view = NineBySixChessboardView();
  const BoardViewFinder finder(ChessboardOf(9, 6));
  std::string why;
  const std::optional<CalibrationView> found = finder.Find(view, "view.png", &why);
  ASSERT_TRUE(found.has_value()) << why;
  EXPECT_LE(finder.chessboard_work().classic_pixels, kClassicDetectorMaxPixels);
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = ChessboardPose();
  ASSERT_EQ(found->image_points.size(), 54u);
  double sum_squares = 0;
  for (size_t i = 0; i < found->image_points.size(); ++i) {
    const cv::Point3f& q = found->object_points[i];
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(X_CT * Eigen::Vector3d(q.x, q.y, q.z), &uv));
    sum_squares +=
        (uv - Eigen::Vector2d(found->image_points[i].x, found->image_points[i].y)).squaredNorm();
  }
  EXPECT_LT(std::sqrt(sum_squares / 54.0), 0.1) << "px, RMS against the rendered truth";
}

}  // namespace
}  // namespace h4::cam
