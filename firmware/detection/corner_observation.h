// A board corner seen in an image: the detector's output and the pose estimator's input.
#pragma once

#include <Eigen/Core>

namespace h4::cam {

/// A corner's pixel displacement per unit of the standardised fit noise of the four sides
/// of its edge group (two columns per side: its angle and offset, whitened): the corners of
/// a tag share these sources, so cov(corner i, corner j) = N_i N_j^T within a group.
using CornerNoisePx = Eigen::Matrix<double, 2, 8>;

struct CornerObservation {
  int id = -1;                                     ///< BoardModel corner id
  Eigen::Vector3d p_TQ = Eigen::Vector3d::Zero();  ///< position on the board (frame T), m
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();    ///< pixel, OpenCV convention
  /// Displacement of `uv` (px) per pixel of erosion of the dark feature the corner belongs
  /// to (its sides moving inward along their normals, as a concave response or a bright
  /// halo does to a dark tag under blur). Zero for corners that do not move under a uniform
  /// erosion (chessboard saddle points, X-corners) or whose sides are not known; the pose
  /// estimator fits the erosion as a nuisance parameter when some corners carry one.
  Eigen::Vector2d erosion_px = Eigen::Vector2d::Zero();
  /// Corners measured from the same edges share this number (an AprilTag's four corners
  /// are the intersections of its four fitted sides, so their errors are correlated); -1
  /// for a corner measured on its own. The pose covariance treats each group as one unit.
  int edge_group = -1;
  /// How the edge fits' pixel noise moves this corner (CornerNoisePx); zero when unknown
  /// (corners not measured by edge fits, or from an older detector).
  CornerNoisePx noise_px = CornerNoisePx::Zero();
};

}  // namespace h4::cam
