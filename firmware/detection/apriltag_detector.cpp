// libapriltag wrapper; see apriltag_detector.h.
#include "firmware/detection/apriltag_detector.h"

#include <algorithm>

#include <apriltag/apriltag.h>
#include <fmt/format.h>

#include "common/formats/image_size.h"
#include <opencv2/imgproc.hpp>

namespace h4::cam {

AprilTagDetector::AprilTagDetector(const AprilTagOptions& options) {
  family_ = CreateTagFamily(options.family, options.border_cells);
  if (!family_) {
    error_ = fmt::format("unsupported tag family '{}' with a {}-cell border", options.family,
                         options.border_cells);
    return;
  }
  detector_ = apriltag_detector_create();
  apriltag_detector_add_family_bits(detector_, family_.get(), options.max_bits_corrected);
  detector_->quad_decimate = options.quad_decimate;
  detector_->quad_sigma = options.quad_sigma;
  detector_->refine_edges = options.refine_edges;
  detector_->decode_sharpening = options.decode_sharpening;
  detector_->nthreads = options.threads;
  detector_->debug = false;
  open_contacts_px_ = std::max(options.open_contacts_px, 0);
}

AprilTagOptions AprilTagOptionsFor(const AprilGridSpec& grid, AprilTagOptions base) {
  base.family = grid.tag_family;
  base.border_cells = grid.design().border_cells;
  if (grid.design().corner_squares) base.open_contacts_px = std::max(base.open_contacts_px, 1);
  if (grid.design().border_cells > 1) base.quad_decimate = std::min(base.quad_decimate, 1.5f);
  return base;
}

int AprilTagDetector::border_cells() const { return family_ ? family_->width_at_border : 0; }

AprilTagDetector::~AprilTagDetector() {
  if (detector_ != nullptr) apriltag_detector_destroy(detector_);
}

std::vector<TagDetection> AprilTagDetector::Detect(const cv::Mat& gray8) const {
  return DetectAll(gray8, true);
}

std::vector<TagDetection> AprilTagDetector::DetectCandidates(const cv::Mat& gray8) const {
  return DetectAll(gray8, false);
}

std::vector<TagDetection> AprilTagDetector::DetectAll(const cv::Mat& gray8, bool skip_known) const {
  std::vector<TagDetection> out;
  if (detector_ == nullptr || gray8.empty() || gray8.type() != CV_8UC1) return out;
  // libapriltag crashes on an image 4 px high or less (issue 42 point 1); no tag fits in
  // one below the smallest side anyway (image_size.h).
  if (gray8.cols < kMinImageSide_px || gray8.rows < kMinImageSide_px) return out;
  Search(gray8, 0, skip_known, &out);
  if (open_contacts_px_ > 0) {
    const int size = 2 * open_contacts_px_ + 1;
    cv::Mat opened;  // a new buffer: the caller's image stays as it is
    cv::dilate(gray8, opened, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(size, size)));
    Search(opened, 1, skip_known, &out);
  }
  return out;
}

void AprilTagDetector::Search(const cv::Mat& gray8, int search, bool skip_known,
                              std::vector<TagDetection>* out) const {
  image_u8_t image{gray8.cols, gray8.rows, static_cast<int32_t>(gray8.step[0]),
                   const_cast<uint8_t*>(gray8.ptr<uint8_t>(0))};
  zarray_t* detections = apriltag_detector_detect(detector_, &image);
  const size_t found_before = out->size();
  for (int i = 0; i < zarray_size(detections); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(detections, i, &det);
    const bool known = std::any_of(out->begin(), out->begin() + static_cast<long>(found_before),
                                   [&](const TagDetection& tag) { return tag.id == det->id; });
    if (skip_known && known) continue;
    TagDetection tag;
    tag.search = search;
    tag.id = det->id;
    tag.hamming = det->hamming;
    tag.decision_margin = det->decision_margin;
    for (int k = 0; k < 4; ++k) {
      tag.corners_px[static_cast<size_t>(k)] =
          Eigen::Vector2d(det->p[k][0], det->p[k][1]) + Eigen::Vector2d::Constant(kCornerOffsetPx);
    }
    out->push_back(tag);
  }
  apriltag_detections_destroy(detections);
}

}  // namespace h4::cam
