// X-corner refinement of Kalibr aprilgrid tag corners; see x_corner_refinement.h.
#include "firmware/detection/x_corner_refinement.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

namespace h4::cam {

bool XCornerOptions::IsValid(std::string* why) const {
  if (!(window_fraction > 0.0 && window_fraction <= 1.0)) {
    *why = fmt::format("window_fraction must be in (0, 1], got {:f}", window_fraction);
    return false;
  }
  if (min_half_window_px < 1 || max_half_window_px < min_half_window_px) {
    *why = "half windows must satisfy 1 <= min_half_window_px <= max_half_window_px";
    return false;
  }
  if (!(max_shift_px > 0.0) || max_iterations < 1 || !(epsilon_px > 0.0)) {
    *why = "max_shift_px, max_iterations and epsilon_px must be positive";
    return false;
  }
  return true;
}

double XRadiusOfSide(int border_cells, int tag_width_cells, double tag_spacing) {
  if (tag_width_cells <= 0) return 0;
  return std::min(static_cast<double>(border_cells) / tag_width_cells, tag_spacing);
}

int XCornerHalfWindow(const XCornerOptions& options, double x_radius_of_side, double side_px) {
  const double radius_px = x_radius_of_side * side_px;
  const int half = static_cast<int>(std::floor(options.window_fraction * radius_px));
  return std::clamp(half, options.min_half_window_px, options.max_half_window_px);
}

namespace {

float Bilinear(const cv::Mat& image32f, const Eigen::Vector2d& p) {
  cv::Mat patch;
  cv::getRectSubPix(image32f, cv::Size(1, 1),
                    cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())), patch);
  return patch.at<float>(0, 0);
}

// An X-corner of a tag: dark towards the tag and away from it (the corner square), light
// on both sides (the gaps), sampled along the bisectors of the tag's two sides at the
// corner. A corner that libapriltag placed elsewhere (a quad fused with a square) fails.
bool LooksLikeTheTagsXCorner(const cv::Mat& image32f, const Eigen::Vector2d& corner,
                             const Eigen::Vector2d& next, const Eigen::Vector2d& previous,
                             double distance_px) {
  const Eigen::Vector2d a = (next - corner).normalized(), b = (previous - corner).normalized();
  const Eigen::Vector2d inward = (a + b).normalized(), across = (a - b).normalized();
  const float dark = std::max(Bilinear(image32f, corner + distance_px * inward),
                              Bilinear(image32f, corner - distance_px * inward));
  const float light = std::min(Bilinear(image32f, corner + distance_px * across),
                               Bilinear(image32f, corner - distance_px * across));
  return dark < light;
}

}  // namespace

int RefineEachXCorner(const cv::Mat& image32f, const XCornerOptions& options,
                      double x_radius_of_side, std::array<Eigen::Vector2d, 4>* corners,
                      std::array<bool, 4>* refined) {
  const std::array<Eigen::Vector2d, 4> quad = *corners;
  int count = 0;
  for (size_t k = 0; k < 4; ++k) {
    (*refined)[k] = false;
    // The two tag sides that meet at corner k set the scale of the X around it.
    const double side_px =
        0.5 * ((quad[(k + 1) % 4] - quad[k]).norm() + (quad[(k + 3) % 4] - quad[k]).norm());
    const int half = XCornerHalfWindow(options, x_radius_of_side, side_px);
    const Eigen::Vector2d start = quad[k];
    // cornerSubPix needs the whole window (plus one pixel for the gradient) in the image.
    if (start.x() < half + 1 || start.y() < half + 1 || start.x() > image32f.cols - half - 2 ||
        start.y() > image32f.rows - half - 2) {
      continue;
    }
    std::vector<cv::Point2f> point{
        cv::Point2f(static_cast<float>(start.x()), static_cast<float>(start.y()))};
    cv::cornerSubPix(image32f, point, cv::Size(half, half), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT,
                                      options.max_iterations, options.epsilon_px));
    const Eigen::Vector2d moved(point[0].x, point[0].y);
    if (!moved.allFinite() || (moved - start).norm() > options.max_shift_px ||
        !LooksLikeTheTagsXCorner(image32f, moved, quad[(k + 1) % 4], quad[(k + 3) % 4],
                                 0.5 * x_radius_of_side * side_px)) {
      continue;
    }
    (*corners)[k] = moved;
    (*refined)[k] = true;
    ++count;
  }
  return count;
}

bool RefineXCorners(const cv::Mat& image32f, const XCornerOptions& options, double x_radius_of_side,
                    std::array<Eigen::Vector2d, 4>* corners) {
  std::array<Eigen::Vector2d, 4> refined = *corners;
  std::array<bool, 4> ok{};
  if (RefineEachXCorner(image32f, options, x_radius_of_side, &refined, &ok) < 4) return false;
  *corners = refined;
  return true;
}

}  // namespace h4::cam
