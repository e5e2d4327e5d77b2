// Sub-pixel refinement of a dark quadrilateral's corners (an AprilTag's outer black
// border on its white quiet zone) by fitting each side as a step edge blurred by a
// Gaussian (sigma s) and integrated over each pixel,
//   I(q) = a + b * F(n . q - c; s),
// to the pixels of a band around the side, in ideal (undistorted) coordinates where the
// side is a straight line; the corners are the intersections of adjacent sides. Unlike
// a gradient-based corner detector this is not pulled inward by the rounding of a
// blurred L-shaped corner: the pixels next to the corners are left out.
#pragma once

#include <array>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "firmware/detection/corner_observation.h"
#include "firmware/detection/ideal_pixel_map.h"

namespace h4::cam {

/// Where the image's blur acted. A lens blurs the light before the pixels integrate it
/// (kOptical, the profile above); an ISP's demosaicing and filters, or a renderer that blurs
/// its pixels, blur the integrated pixel values (kPixel: a sampled Gaussian kernel over
/// neighbouring pixels that integrated a step the lens blurred a little). On sides along the
/// pixel axes the two profiles differ in shape.
enum class BlurStage { kOptical, kPixel };

struct EdgeFitOptions {
  double band_px = 2.5;  ///< half width of the pixel band fitted around a side
  /// Width of the quad in cells (libapriltag's width_at_border: 8 for tag36h11, 10 with
  /// Kalibr's 2-cell border): the dark side of the band stays clear of the black border's
  /// inner edge, where a white data cell would bias the fit. 0 = no such limit.
  int tag_width_cells = 0;
  /// Thickness of the black border in cells (1: libapriltag's tags, 2: Kalibr's): the
  /// inner edge lies this many cells inside each side.
  int border_thickness_cells = 1;
  /// Clearance of the band's dark side from the border's inner edge: this many pixels plus
  /// `inner_clearance_blur` times the fitted blur sigma (the blurred inner edge's tail
  /// reaches ~3 sigma into the border; which data cells are white differs per side, so the
  /// tail pulls each side differently and the quad rotates). The dark side keeps at least
  /// 1 px. Used only with tag_width_cells > 0.
  double inner_clearance_px = 2.5;
  double inner_clearance_blur = 0.0;
  /// Also fit the inner edge's tail that still reaches the band where the data cell next to
  /// the border is white (cells read from the image at their centres),
  /// I = a + b (F(d) + w(t) (1 - F(d + thickness))): a wider clearance would leave too few
  /// dark pixels on borders of 5-7 px. Used only with tag_width_cells > 0.
  bool model_inner_edge = true;
  double corner_clearance_px = 3.0;  ///< pixels this close to a corner (along the side) skipped
  int passes = 2;                    ///< select the band around the current line this many times
  int iterations = 5;                ///< Gauss-Newton iterations per pass
  double max_shift_px = 2.0;         ///< a corner moving farther than this fails the refinement
  int min_pixels = 12;               ///< fewer pixels in a side's band fails the refinement
  /// A side whose RMS fit residual exceeds this fraction of its contrast fails (the band
  /// holds something other than a clean blurred step: an occluder, a shadow edge).
  double max_residual = 0.04;
  /// Sides within this angle of a pixel axis are also fitted with a pixel blur where a short
  /// screening fit says it may fit better, and keep it where it clearly does (with the wrong
  /// profile they lock to the pixel grid); 0: optical only.
  double pixel_blur_check_deg = 6.0;
  /// Fit the light changing linearly along each side (an illumination gradient or
  /// vignetting scales the side's dark and bright levels together); with constant levels
  /// the fitted side tilts toward its darker end.
  bool fit_shading = true;
};

/// Refines `corners` (distorted pixels, OpenCV convention, in order around the quad) in
/// place from a CV_32FC1 image. Returns false and leaves them untouched when a side
/// cannot be fitted (too few pixels, no contrast, poor fit, corner moved too far).
/// When `erosion_px` is given, it receives for each corner its pixel displacement per pixel
/// of uniform erosion of the quad (every side moving inward along its normal by one image
/// pixel): a side's edge fit is biased that way when the image's response is not linear
/// (corner_observation.h).
/// When `noise_px` is given, it receives for each corner its pixel displacement per unit of
/// the four sides' standardised fit noise (corner_observation.h: CornerNoisePx), from the
/// pixel noise each side's residuals show.
bool RefineQuadCorners(const cv::Mat& image32f, const IdealPixelMap& map,
                       const EdgeFitOptions& options, std::array<Eigen::Vector2d, 4>* corners,
                       std::array<Eigen::Vector2d, 4>* erosion_px = nullptr,
                       std::array<CornerNoisePx, 4>* noise_px = nullptr);

}  // namespace h4::cam
