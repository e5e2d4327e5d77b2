// Chessboard inner corners with OpenCV (findChessboardCornersSB, then the classic
// detector as a fallback), refined with cornerSubPix (unbiased on X-shaped corners) and
// put in the board model's order: row-major from the corner next to the black top-left
// square, x along a row. The classic detector runs on a copy reduced to at most
// kClassicDetectorMaxPixels: asked for a corner count the image does not show, its search
// grows with the image (measured: 74 s on a clean 2028 x 1520 view of a 9 x 6 board asked
// for 8 x 6; 0.27 s on its 640 x 480 copy).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/board/board_spec.h"

namespace h4::cam {

/// The most pixels cv::findChessboardCorners (the classic detector) is given: VGA.
constexpr int64_t kClassicDetectorMaxPixels = 640 * 480;

/// The work a chessboard search did, for tests that bound it without a clock.
struct ChessboardWork {
  int64_t classic_pixels = 0;  ///< pixels given to the classic detector, all runs summed
};

/// cv::findChessboardCorners(image8, pattern, corners, flags) on image8 reduced (INTER_AREA)
/// to at most kClassicDetectorMaxPixels, the corners mapped back to image8's pixels (not
/// refined: the caller runs cornerSubPix at full resolution). Adds to `work` when given.
bool FindChessboardCornersBounded(const cv::Mat& image8, cv::Size pattern, int flags,
                                  std::vector<cv::Point2f>* corners,
                                  ChessboardWork* work = nullptr);

/// All spec.cols x spec.rows inner corners or nothing (returns false). The 180-degree
/// ambiguity is resolved from the colour of the top-left square when cols + rows is odd;
/// for boards symmetric under that rotation OpenCV's order is kept.
bool FindChessboardCorners(const cv::Mat& image8, const cv::Mat& image32,
                           const CheckerboardSpec& spec, int subpix_half_window,
                           std::vector<Eigen::Vector2d>* uv, ChessboardWork* work = nullptr);

}  // namespace h4::cam
