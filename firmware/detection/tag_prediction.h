// Finding the tags of a known AprilTag grid that the quad search missed, by following the
// lens: a first board pose X_CT is fitted through the camera model to the tags found, every
// other tag of the board is projected through the same model (a fisheye compresses and
// bends tags into shapes libapriltag's straight-sided quads do not fit, and small tags
// fall through its segmentation), and a tag whose whole border is inside the image is
// accepted only when the cells read there, sampled through the camera model, carry the
// code of that tag id (at most a few bits wrong: tag36h11's codes differ in 11 or more).
// The caller then refines its corners like any other tag's.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/detection/corner_observation.h"

namespace h4::cam {

struct TagPredictionOptions {
  /// Predict the missing tags of an AprilTag grid from the found ones (false: libapriltag's
  /// tags only, as before).
  bool enabled = true;
  /// Tags found by the quad search needed before predicting (a pose from one tag's four
  /// corners is too loose to predict far ones).
  int min_tags = 2;
  /// RMS reprojection error of a found tag under the first pose, px, above which that tag
  /// is taken for a misplaced detection, dropped from the fit, and the pose refitted.
  double max_tag_rms_px = 1.5;
  /// Every point of a predicted tag's outer border must be this far inside the image, px.
  double image_margin_px = 2.0;
  /// A predicted tag's data cells that may read other than its code: tag36h11's codes
  /// differ in at least 11 bits, so a reading within 5 of the expected code is farther from
  /// every other (the decoding radius (11 - 1) / 2). Measured on 20 px tags of a rendered
  /// 512 x 512 fisheye view: true tags read with up to 5 cells wrong, other ids' codes
  /// with 12 or more (tests/render/fisheye_detection_test.cpp).
  int max_code_errors = 5;
  /// Black border cells that may read white (blur across a 2 px cell, a glint).
  int max_border_errors = 2;
  /// Grey levels the quiet zone around a predicted tag must be brighter than its border.
  double min_contrast = 10.0;
};

/// Why a tag of the board that lies wholly in the image is not in the detection
/// (`preview --draw` writes it beside the tag).
enum class TagMiss {
  kNotFound,          ///< nothing tag-like at the predicted place (no contrast)
  kFailedCode,        ///< the cells there do not carry the tag's code
  kFailedRefinement,  ///< the code is right but the corners could not be refined
};
const char* ToString(TagMiss why);

/// A tag of the board predicted wholly inside the image but left out, and why.
struct MissedTag {
  int tag_id = -1;
  std::array<Eigen::Vector2d, 4> corners_px;  ///< predicted, libapriltag's corner order
  TagMiss why = TagMiss::kNotFound;
  int code_errors = -1;  ///< data cells read wrong (kFailedCode, kFailedRefinement)
};

/// What the cells at a predicted tag's place say.
struct TagCodeReading {
  double contrast = 0;    ///< quiet zone minus border, grey levels
  int code_errors = 0;    ///< data cells that disagree with the expected code
  int border_errors = 0;  ///< border cells that read white
};

/// X_CT fitted through `camera` to `corners` (weights equal), starting from IPPE on their
/// undistorted rays; corners whose ray is 90 degrees or more off-axis are left out.
/// False when fewer than 4 corners remain or the fit fails. `rms_px` of the fitted corners.
bool FitPoseToCorners(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                      RigidTransform* X_CT, double* rms_px);

/// The pixel corners of tag `tag_index` (board order) at pose X_CT, when points along its
/// whole outer border project at least `margin_px` inside the image; false otherwise.
bool PredictTagCorners(const BoardModel& board, const CameraModel& camera,
                       const RigidTransform& X_CT, int tag_index, double margin_px,
                       std::array<Eigen::Vector2d, 4>* corners_px);

/// The expected cells of every tag of a grid, read back at predicted places.
class TagCodeReader {
 public:
  /// The codes of `grid`'s tags (its family, first id and border width).
  TagCodeReader(const BoardModel& board, const AprilGridSpec& grid);

  bool ok() const { return width_ > 0; }
  /// The cells of tag `tag_index` sampled at pose X_CT through `camera` in a CV_32FC1
  /// image, compared with its code.
  TagCodeReading Read(const cv::Mat& image32, const CameraModel& camera, const RigidTransform& X_CT,
                      int tag_index) const;

 private:
  /// Mean grey level near the point (s, t) of the tag (fractions of its side from its
  /// top-left corner), or NaN when a sample falls outside the image.
  double SampleCell(const cv::Mat& image32, const CameraModel& camera, const RigidTransform& X_CT,
                    int tag_index, double s, double t) const;
  std::vector<double> SharpenedCells(const cv::Mat& image32, const CameraModel& camera,
                                     const RigidTransform& X_CT, int tag_index, double white) const;
  bool InBorder(int row, int col) const;
  double QuietZoneLevel(const cv::Mat& image32, const CameraModel& camera,
                        const RigidTransform& X_CT, int tag_index) const;

  BoardModel board_;
  std::vector<std::vector<bool>> cells_;  // per tag index, width x width, true = white
  int width_ = 0;                         // cells across a tag up to its outer border edge
  int border_cells_ = 1;
  double quiet_offset_cells_ = 1.0;  // how far outside the border the quiet zone is read
  double sharpening_ = 0.25;         // libapriltag's default decode_sharpening
};

}  // namespace h4::cam
