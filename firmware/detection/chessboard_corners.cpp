// Chessboard corners; see chessboard_corners.h.
#include "firmware/detection/chessboard_corners.h"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace h4::cam {

bool FindChessboardCornersBounded(const cv::Mat& image8, cv::Size pattern, int flags,
                                  std::vector<cv::Point2f>* corners, ChessboardWork* work) {
  const double pixels = static_cast<double>(image8.cols) * image8.rows;
  if (pixels <= static_cast<double>(kClassicDetectorMaxPixels)) {
    if (work != nullptr) work->classic_pixels += static_cast<int64_t>(pixels);
    return cv::findChessboardCorners(image8, pattern, *corners, flags);
  }
  const double scale = std::sqrt(static_cast<double>(kClassicDetectorMaxPixels) / pixels);
  const cv::Size reduced_size(std::max(1, static_cast<int>(image8.cols * scale)),
                              std::max(1, static_cast<int>(image8.rows * scale)));
  cv::Mat reduced;
  cv::resize(image8, reduced, reduced_size, 0, 0, cv::INTER_AREA);
  if (work != nullptr) work->classic_pixels += int64_t{reduced.cols} * reduced.rows;
  if (!cv::findChessboardCorners(reduced, pattern, *corners, flags)) return false;
  // Pixel centres: (0, 0) is the centre of the top-left pixel at both sizes.
  const float sx = static_cast<float>(image8.cols) / static_cast<float>(reduced.cols);
  const float sy = static_cast<float>(image8.rows) / static_cast<float>(reduced.rows);
  for (cv::Point2f& p : *corners) p = {(p.x + 0.5f) * sx - 0.5f, (p.y + 0.5f) * sy - 0.5f};
  return true;
}

bool FindChessboardCorners(const cv::Mat& image8, const cv::Mat& image32,
                           const CheckerboardSpec& spec, int subpix_half_window,
                           std::vector<Eigen::Vector2d>* uv, ChessboardWork* work) {
  const cv::Size size(spec.cols, spec.rows);
  if (spec.cols < 2 || spec.rows < 2) return false;
  std::vector<cv::Point2f> points;
  bool found = cv::findChessboardCornersSB(image8, size, points,
                                           cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE);
  if (!found) {
    found = FindChessboardCornersBounded(
        image8, size, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE, &points, work);
  }
  if (!found || points.size() != static_cast<size_t>(spec.cols * spec.rows)) return false;
  const int w = subpix_half_window;
  cv::cornerSubPix(image32, points, cv::Size(w, w), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 1e-4));

  auto at = [&](int row, int col) -> cv::Point2f& {
    return points[static_cast<size_t>(row * spec.cols + col)];
  };
  // Board x cross board y must point into the image as u cross v does (z into the board).
  const cv::Point2f x_axis = at(0, 1) - at(0, 0);
  const cv::Point2f y_axis = at(1, 0) - at(0, 0);
  if (x_axis.x * y_axis.y - x_axis.y * y_axis.x < 0) {
    for (int row = 0; row < spec.rows; ++row) {
      std::reverse(points.begin() + row * spec.cols, points.begin() + (row + 1) * spec.cols);
    }
  }
  if ((spec.cols + spec.rows) % 2 == 1) {
    // The square up-left of corner (0, 0) is black: sample its middle.
    const cv::Point2f probe = at(0, 0) - 0.5f * (at(1, 1) - at(0, 0));
    const cv::Point2f white = at(0, 0) + 0.5f * (at(1, 0) - at(0, 0)) -
                              0.5f * (at(0, 1) - at(0, 0));  // left of (0, 0): white
    auto grey = [&](const cv::Point2f& p) {
      const int u = std::clamp(static_cast<int>(p.x + 0.5f), 0, image32.cols - 1);
      const int v = std::clamp(static_cast<int>(p.y + 0.5f), 0, image32.rows - 1);
      return image32.at<float>(v, u);
    };
    if (grey(probe) > grey(white)) std::reverse(points.begin(), points.end());
  }
  uv->clear();
  for (const cv::Point2f& p : points) uv->emplace_back(p.x, p.y);
  return true;
}

}  // namespace h4::cam
