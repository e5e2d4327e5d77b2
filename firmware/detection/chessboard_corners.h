// Chessboard inner corners with OpenCV (findChessboardCornersSB, then the classic
// detector as a fallback), refined with cornerSubPix (unbiased on X-shaped corners) and
// put in the board model's order: row-major from the corner next to the black top-left
// square, x along a row.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/board/board_spec.h"

namespace h4::cam {

/// All spec.cols x spec.rows inner corners or nothing (returns false). The 180-degree
/// ambiguity is resolved from the colour of the top-left square when cols + rows is odd;
/// for boards symmetric under that rotation OpenCV's order is kept.
bool FindChessboardCorners(const cv::Mat& image8, const cv::Mat& image32,
                           const CheckerboardSpec& spec, int subpix_half_window,
                           std::vector<Eigen::Vector2d>* uv);

}  // namespace h4::cam
