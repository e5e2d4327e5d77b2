// Sub-pixel refinement of the corners of a tag on Kalibr's aprilgrid, where every tag
// corner is an X-corner: the tag's black border and a black corner square meet at the
// corner, with white gap on the two other sides. Near such a saddle the image is point
// symmetric about the corner whatever the (symmetric) blur and whatever the monotonic
// response curve of the camera, so the gradient-orthogonality estimate of OpenCV's
// cornerSubPix lands on the corner itself; on a lone L-corner (h4cam's legacy tags) the
// same estimate is pulled inward by blur. The window stays inside the region where the
// pattern is an X: within the tag's 2-cell black border and within the corner square.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace h4::cam {

struct XCornerOptions {
  /// Half window of cornerSubPix as a fraction of the corner's X radius (the smaller of
  /// the tag's black border and the corner square's side, measured in the image).
  double window_fraction = 0.8;
  int min_half_window_px = 2;   ///< smallest half window, px (a 5 x 5 window)
  int max_half_window_px = 12;  ///< largest half window, px
  /// A corner moving farther than this fails the refinement, px (the detector's corners
  /// start up to 1.4 px inside: apriltag_detector.h open_contacts_px).
  double max_shift_px = 3.0;
  int max_iterations = 40;   ///< cornerSubPix iterations
  double epsilon_px = 1e-4;  ///< cornerSubPix stops when a step is shorter than this

  bool IsValid(std::string* why) const;
};

/// Refines the four corners (distorted pixels, OpenCV convention, in order around the
/// tag) of one tag in place from a CV_32FC1 image. `x_radius_of_side` is the X radius as a
/// fraction of the tag side (board_spec.h: min(border_cells / tag width in cells,
/// tagSpacing)). Returns false and leaves the corners untouched when a corner leaves the
/// image, moves more than max_shift_px, or is not an X-corner of this tag (dark towards
/// the tag and away from it, light on both sides, half an X radius away).
bool RefineXCorners(const cv::Mat& image32f, const XCornerOptions& options, double x_radius_of_side,
                    std::array<Eigen::Vector2d, 4>* corners);

/// The same, corner by corner: refines those that pass the checks above, leaves the others
/// untouched, sets `refined[k]` accordingly and returns how many were refined. Small tags
/// in real photographs (25-35 px) often have one corner whose window reaches a neighbour
/// or the board's edge: the tag's other corners stay usable.
int RefineEachXCorner(const cv::Mat& image32f, const XCornerOptions& options,
                      double x_radius_of_side, std::array<Eigen::Vector2d, 4>* corners,
                      std::array<bool, 4>* refined);

/// X radius as a fraction of the tag side for tags `tag_width_cells` wide with a black border
/// of `border_cells` and corner squares of `tag_spacing` tag sides: the X ends where the
/// border or the square ends.
double XRadiusOfSide(int border_cells, int tag_width_cells, double tag_spacing);

/// Half window (px) for a corner whose adjacent tag sides measure `side_px` in the image.
int XCornerHalfWindow(const XCornerOptions& options, double x_radius_of_side, double side_px);

}  // namespace h4::cam
