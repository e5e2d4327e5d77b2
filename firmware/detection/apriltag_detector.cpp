// libapriltag wrapper; see apriltag_detector.h.
#include "firmware/detection/apriltag_detector.h"

#include <apriltag/apriltag.h>

namespace h4::cam {

AprilTagDetector::AprilTagDetector(const AprilTagOptions& options) {
  family_ = CreateTagFamily(options.family);
  if (!family_) {
    error_ = "unsupported tag family '" + options.family + "'";
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
}

int AprilTagDetector::border_cells() const { return family_ ? family_->width_at_border : 0; }

AprilTagDetector::~AprilTagDetector() {
  if (detector_ != nullptr) apriltag_detector_destroy(detector_);
}

std::vector<TagDetection> AprilTagDetector::Detect(const cv::Mat& gray8) const {
  std::vector<TagDetection> out;
  if (detector_ == nullptr || gray8.empty() || gray8.type() != CV_8UC1) return out;
  image_u8_t image{gray8.cols, gray8.rows, static_cast<int32_t>(gray8.step[0]),
                   const_cast<uint8_t*>(gray8.ptr<uint8_t>(0))};
  zarray_t* detections = apriltag_detector_detect(detector_, &image);
  for (int i = 0; i < zarray_size(detections); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(detections, i, &det);
    TagDetection tag;
    tag.id = det->id;
    tag.hamming = det->hamming;
    tag.decision_margin = det->decision_margin;
    for (int k = 0; k < 4; ++k) {
      tag.corners_px[static_cast<size_t>(k)] =
          Eigen::Vector2d(det->p[k][0], det->p[k][1]) + Eigen::Vector2d::Constant(kCornerOffsetPx);
    }
    out.push_back(tag);
  }
  apriltag_detections_destroy(detections);
  return out;
}

}  // namespace h4::cam
