// Average -> detect -> pose; see measure_pipeline.h.
#include "firmware/pose/measure_pipeline.h"

#include <algorithm>
#include <variant>

#include <fmt/format.h>

namespace h4::cam {
namespace {

// The corners the pose was fitted to, with their tag and noise, to travel with the pose
// (common/formats/README.md#board-corners-csv: the tag of corner id 4 * (tag - firstId) + k,
// -1 on a chessboard), as the camera model sees them: less the displacement the fitted
// erosion explains (pose_estimator.h), which a fit in pixel space downstream (the corner
// path) would otherwise read as a smaller board, i.e. a wrong focal length.
std::vector<MeasuredCorner> MeasuredCorners(const BoardModel& board,
                                            const std::vector<CornerObservation>& corners,
                                            const PoseEstimate& pose) {
  const std::vector<double>& sigma_px = pose.corner_sigma_px;
  const std::vector<Eigen::Vector2d>& erosion_px = pose.corner_erosion_px;
  const auto* grid = std::get_if<AprilGridSpec>(&board.spec());
  std::vector<MeasuredCorner> measured;
  measured.reserve(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    MeasuredCorner m;
    m.tag_id = grid != nullptr ? grid->first_id + corners[i].id / 4 : -1;
    m.corner = corners[i].id;
    m.uv = corners[i].uv;
    if (i < erosion_px.size()) {
      m.erosion_px = erosion_px[i];
      m.uv -= erosion_px[i];
    }
    m.sigma_px = i < sigma_px.size() ? sigma_px[i] : 0.0;
    measured.push_back(m);
  }
  return measured;
}

}  // namespace

std::vector<h4::CornerObservation> CornerRows(const Measurement& m, int64_t pose_id) {
  std::vector<h4::CornerObservation> rows;
  rows.reserve(m.corners.size());
  for (const MeasuredCorner& c : m.corners) {
    h4::CornerObservation row;
    row.pose_id = pose_id;
    row.tag_id = c.tag_id;
    row.corner = c.corner;
    row.u = c.uv.x();
    row.v = c.uv.y();
    row.sigma_px = std::clamp(c.sigma_px, kCornerSigmaBounds.min, kCornerSigmaBounds.max);
    rows.push_back(row);
  }
  return rows;
}

bool PipelineOptions::IsValid(std::string* why) const {
  if (frames < 1) {
    if (why != nullptr) *why = "frames per measurement must be >= 1";
    return false;
  }
  if (!(motion.max_spread_px > 0)) {
    if (why != nullptr) *why = "motion threshold must be > 0 px";
    return false;
  }
  return true;
}

MeasurePipeline::MeasurePipeline(const BoardSpec& board, const CameraIntrinsics& camera,
                                 const PipelineOptions& options)
    : options_(options),
      camera_(camera),
      detector_(board, camera, options.detector),
      averager_(options.frames) {
  if (!options_.IsValid(&error_)) return;
  if (!detector_.ok()) error_ = detector_.error();
}

std::optional<Measurement> MeasurePipeline::AddFrame(const Frame& frame) {
  if (!averager_.Add(frame)) {
    Measurement m;
    m.status = Measurement::Status::kCameraError;
    m.message = averager_.error();
    m.utime = frame.utime;
    m.origin = frame.origin;
    averager_.Reset();
    return m;
  }
  if (!averager_.complete()) return std::nullopt;
  return MeasureGroup();
}

Measurement MeasurePipeline::Finish() {
  if (averager_.count() == 0) {
    Measurement m;
    m.message = "no frame";
    return m;
  }
  return MeasureGroup();
}

Measurement MeasurePipeline::MeasureFrames(const std::vector<Frame>& frames) {
  averager_.Reset();
  for (const Frame& frame : frames) {
    if (!averager_.Add(frame)) {
      Measurement m;
      m.status = Measurement::Status::kCameraError;
      m.message = averager_.error();
      m.origin = frames.front().origin;
      averager_.Reset();
      return m;
    }
  }
  return Finish();
}

Measurement MeasurePipeline::MeasureImage(const cv::Mat& image, int frames_averaged) const {
  Measurement m;
  m.frames_averaged = frames_averaged;
  if (!ok()) {
    m.status = Measurement::Status::kCameraError;
    m.message = error_;
    return m;
  }
  const BoardDetection detection = detector_.Detect(image);
  m.corners_used = static_cast<int>(detection.corners.size());
  // Tags whose id was decoded twice are dropped (a second board, or a misdecode): say so,
  // or two boards in view read as if no board had been seen at all.
  const std::string seen_twice =
      detection.ids_seen_twice == 0
          ? std::string()
          : fmt::format("; {} tag id(s) were seen twice and not used (two boards in view?)",
                        detection.ids_seen_twice);
  if (detection.status == BoardDetection::Status::kNoBoard) {
    m.status = Measurement::Status::kNoBoard;
    m.message = "no board corner found" + seen_twice;
    return m;
  }
  if (detection.status == BoardDetection::Status::kPartial) {
    m.status = Measurement::Status::kPartial;
    m.message = fmt::format("{} corners, need {}{}", m.corners_used, options_.detector.min_corners,
                            seen_twice);
    return m;
  }
  const PoseEstimate pose = EstimatePose(detection.corners, camera_, options_.pose);
  if (!pose.ok()) {
    m.status = pose.status == PoseEstimate::Status::kTooFewCorners ? Measurement::Status::kPartial
                                                                   : Measurement::Status::kNoBoard;
    m.message = pose.message;
    return m;
  }
  m.status = Measurement::Status::kOk;
  m.X_CT = pose.X_CT;
  m.covariance = pose.covariance;
  m.sigma_t = pose.sigma_t;
  m.sigma_r = pose.sigma_r;
  m.rms_px = pose.rms_px;
  m.erosion_px = pose.erosion_px;
  m.corners = MeasuredCorners(detector_.board(), detection.corners, pose);
  return m;
}

Measurement MeasurePipeline::MeasureGroup() {
  const cv::Mat mean = averager_.Mean();
  Measurement m = MeasureImage(mean, averager_.count());
  m.utime = averager_.first_utime();
  m.origin = averager_.first_origin();
  if (m.status == Measurement::Status::kOk && averager_.count() > 1) {
    // Corners re-projected from the fitted pose: all board corners that fall in the image,
    // not only those detected, so the spread covers the whole board.
    std::vector<Eigen::Vector2d> corners_px;
    for (const Eigen::Vector3d& p_TQ : detector_.board().corners()) {
      Eigen::Vector2d uv;
      if (camera_.ProjectVisible(m.X_CT * p_TQ, &uv) && uv.x() >= 0 && uv.y() >= 0 &&
          uv.x() <= mean.cols - 1 && uv.y() <= mean.rows - 1) {
        corners_px.push_back(uv);
      }
    }
    const MotionEstimate motion =
        EstimateFrameSpread(averager_.frames(), mean, corners_px, options_.motion);
    m.frame_spread_px = motion.spread_px;
    if (motion.moved) {
      m.status = Measurement::Status::kMoved;
      m.message = fmt::format("board moved during the group: corner spread {:f} px > {:f} px",
                              motion.spread_px, options_.motion.max_spread_px);
    }
  }
  averager_.Reset();
  return m;
}

}  // namespace h4::cam
