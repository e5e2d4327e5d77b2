// libapriltag behind a small RAII wrapper: detects tags in an 8-bit image and returns
// each tag's 4 corners in OpenCV's pixel convention ((0, 0) = centre of the top-left
// pixel). libapriltag 3.3 reports corners shifted from that convention (measured on
// rendered images with known truth, tests/render/apriltag_detector_test.cpp); the shift
// is removed here, at the boundary, and nowhere else.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "common/board/board_spec.h"
#include "firmware/detection/tag_family.h"

struct apriltag_detector;

namespace h4::cam {

struct AprilTagOptions {
  std::string family = "tag36h11";
  /// Black border width of the printed tags, cells: 1 for libapriltag's tags, 2 for
  /// Kalibr's (board_spec.h AprilGridDesign::border_cells).
  int border_cells = 1;
  /// Quad search on an image decimated by this factor (speed); the edges are then
  /// refined on the full image (refine_edges), so the corners keep full resolution.
  float quad_decimate = 2.0f;
  float quad_sigma = 0.0f;          ///< Gaussian blur before quad search, px (0 = none)
  bool refine_edges = true;         ///< snap quad edges to strong gradients, full resolution
  double decode_sharpening = 0.25;  ///< libapriltag's default
  int max_bits_corrected = 1;       ///< decoding tolerance; 1 keeps false positives rare
  int threads = 1;                  ///< one core: the camera module has others to feed
  /// Second search, for the tags the first one missed, on the image dilated by this many
  /// px (white grows), 0 = none. Kalibr's corner squares touch the tags at single points,
  /// which libapriltag's segmentation can take for a connection, fusing tags and squares
  /// into one region with no quad; dilating opens those contacts but also thins the black
  /// data cells, so it only adds tags (measured on two EuRoC frames of Kalibr's board:
  /// 30 -> 33 and 32 -> 35 of 36). Corners from it sit up to px * sqrt(2) inside the tag:
  /// refine them.
  int open_contacts_px = 0;
};

/// `base` set up for the tags of `grid`: its family and border, and on Kalibr's design
/// (2-cell borders, corner squares) the second search that opens the squares' contacts and
/// a finer quad search (a 2-cell border makes the cells of a tag of a given size 20 %
/// smaller: decimated by 2, the search lost 2 of 36 tags on each gamma render of
/// board_detector_test, by 1.5 none, and took no longer there).
AprilTagOptions AprilTagOptionsFor(const AprilGridSpec& grid, AprilTagOptions base = {});

struct TagDetection {
  int id = -1;
  int hamming = 0;             ///< bits corrected when decoding
  double decision_margin = 0;  ///< libapriltag's decoding quality (higher is better)
  int search = 0;              ///< 0: found in the image as given, 1: in the opened image
  /// Corners in libapriltag's order (board_model.h: bottom-left, bottom-right, top-right,
  /// top-left as printed), OpenCV pixel convention.
  std::array<Eigen::Vector2d, 4> corners_px;
};

class AprilTagDetector {
 public:
  /// Offset added to libapriltag's corner output to reach OpenCV's convention, px (both
  /// axes): its corners sit half a pixel right of and below the truth, i.e. it counts
  /// pixel centres at +0.5 (measured: mean offset (+0.498, +0.502) px over 144 corners
  /// at the default options).
  static constexpr double kCornerOffsetPx = -0.5;

  explicit AprilTagDetector(const AprilTagOptions& options = {});
  ~AprilTagDetector();
  AprilTagDetector(const AprilTagDetector&) = delete;
  AprilTagDetector& operator=(const AprilTagDetector&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  /// Width of a tag up to the outer edge of its black border, in cells (8 for tag36h11,
  /// 10 with Kalibr's 2-cell border).
  int border_cells() const;

  /// Tags found in a CV_8UC1 image (any other type, or an image under kMinImageSide_px a side,
  /// common/formats/image_size.h, gives no detection).
  std::vector<TagDetection> Detect(const cv::Mat& gray8) const;
  /// Every detection of both searches (open_contacts_px), a tag id possibly once per
  /// search, first search first: for a caller that checks each candidate (a quad fused
  /// with a corner square decodes but has a misplaced corner) and falls back on the next.
  std::vector<TagDetection> DetectCandidates(const cv::Mat& gray8) const;

 private:
  /// One libapriltag search appended to `out`; with `skip_known`, tags whose id is already
  /// in `out` are skipped.
  void Search(const cv::Mat& gray8, int search, bool skip_known,
              std::vector<TagDetection>* out) const;
  std::vector<TagDetection> DetectAll(const cv::Mat& gray8, bool skip_known) const;

  TagFamilyPtr family_;
  apriltag_detector* detector_ = nullptr;
  int open_contacts_px_ = 0;
  std::string error_;
};

}  // namespace h4::cam
