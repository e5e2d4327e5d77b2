// Predicting and verifying a grid's missed tags; see tag_prediction.h.
#include "firmware/detection/tag_prediction.h"

#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "common/camera/board_pose_fit.h"
#include "common/text/enum_names.h"
#include "firmware/detection/planar_pose_starts.h"
#include "firmware/detection/tag_family.h"

namespace h4::cam {

constexpr EnumNames<TagMiss, TagMiss::kFailedRefinement> kTagMissNames = {
    "not found", "failed code", "failed refinement"};

const char* ToString(TagMiss why) { return kTagMissNames.NameOf(why); }

namespace {

// The corners the pose fit can use (those with a ray IPPE can take: less than 90 degrees
// off-axis), and IPPE's two planar solutions from them: starts for the fit through the
// lens model.
std::vector<RigidTransform> PlanarPoseStartsFromRays(const std::vector<CornerObservation>& corners,
                                                     const CameraModel& camera,
                                                     PoseCorners* fitted) {
  for (const CornerObservation& c : corners) {
    Eigen::Vector2d xn;
    if (!camera.NormalizedFromPixel(c.uv, &xn)) continue;  // 90 degrees or more off-axis
    fitted->p_TQ.push_back(c.p_TQ);
    fitted->uv.push_back(c.uv);
    fitted->weight.push_back(1.0);
  }
  return IppePlanarStarts(corners, camera);
}

double PredictionFitRmsPx(const PoseCorners& corners, const CameraModel& camera,
                          const RigidTransform& X_CT) {
  double sum = 0;
  for (size_t k = 0; k < corners.uv.size(); ++k) {
    Eigen::Vector2d uv;
    if (!camera.Project(X_CT * corners.p_TQ[k], &uv)) return std::numeric_limits<double>::max();
    sum += (uv - corners.uv[k]).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(std::max<size_t>(corners.uv.size(), 1)));
}

// Bilinear grey level at pixel uv of a CV_32FC1 image; NaN outside.
double GreyAtPredictedPixel(const cv::Mat& image32, const Eigen::Vector2d& uv) {
  const double x0 = std::floor(uv.x()), y0 = std::floor(uv.y());
  if (!(x0 >= 0 && y0 >= 0 && x0 + 1 < image32.cols && y0 + 1 < image32.rows)) return NAN;
  const int u = static_cast<int>(x0), v = static_cast<int>(y0);
  const double a = uv.x() - x0, b = uv.y() - y0;
  const float* top = image32.ptr<float>(v);
  const float* bottom = image32.ptr<float>(v + 1);
  return (1 - b) * ((1 - a) * top[u] + a * top[u + 1]) +
         b * ((1 - a) * bottom[u] + a * bottom[u + 1]);
}

}  // namespace

bool FitPoseToCorners(const std::vector<CornerObservation>& corners, const CameraModel& camera,
                      RigidTransform* X_CT, double* rms_px) {
  PoseCorners fitted;
  const std::vector<RigidTransform> starts = PlanarPoseStartsFromRays(corners, camera, &fitted);
  double best = std::numeric_limits<double>::max();
  for (const RigidTransform& start : starts) {
    RigidTransform X;
    if (!FitBoardPose(fitted, camera.intrinsics(), start, &X)) continue;
    const double rms = PredictionFitRmsPx(fitted, camera, X);
    if (rms < best) {
      best = rms;
      *X_CT = X;
    }
  }
  *rms_px = best;
  return best < std::numeric_limits<double>::max();
}

bool PredictTagCorners(const BoardModel& board, const CameraModel& camera,
                       const RigidTransform& X_CT, int tag_index, double margin_px,
                       std::array<Eigen::Vector2d, 4>* corners_px) {
  const size_t first = static_cast<size_t>(tag_index) * 4;
  if (first + 3 >= board.corners().size()) return false;
  // Points along every side, not only the corners: a fisheye bows the sides outward.
  const int steps_per_side = 8;
  for (size_t k = 0; k < 4; ++k) {
    const Eigen::Vector3d& a = board.corners()[first + k];
    const Eigen::Vector3d& b = board.corners()[first + (k + 1) % 4];
    for (int step = 0; step < steps_per_side; ++step) {
      const double f = static_cast<double>(step) / steps_per_side;
      Eigen::Vector2d uv;
      if (!camera.ProjectRay(X_CT * (a + f * (b - a)), &uv)) return false;
      if (!(uv.x() >= margin_px && uv.y() >= margin_px &&
            uv.x() <= camera.width() - 1 - margin_px &&
            uv.y() <= camera.height() - 1 - margin_px)) {
        return false;
      }
      if (step == 0) (*corners_px)[k] = uv;
    }
  }
  return true;
}

TagCodeReader::TagCodeReader(const BoardModel& board, const AprilGridSpec& grid)
    : board_(board), border_cells_(grid.design().border_cells) {
  const TagFamilyPtr family = CreateTagFamily(grid.tag_family);
  if (!family) return;
  const int tags = board.corner_count() / 4;
  int width = 0;
  for (int index = 0; index < tags; ++index) {
    cells_.push_back(TagCells(*family, grid.first_id + index, border_cells_, &width));
    if (cells_.back().empty()) return;  // an id beyond the family: no reader
  }
  // The middle of the gap between tags, at most one cell out: white on every layout (the
  // corner squares of Kalibr's design sit at the tag corners, not beside the sides).
  quiet_offset_cells_ = std::min(1.0, 0.5 * grid.tag_spacing * width);
  width_ = width;
}

double TagCodeReader::SampleCell(const cv::Mat& image32, const CameraModel& camera,
                                 const RigidTransform& X_CT, int tag_index, double s,
                                 double t) const {
  const size_t first = static_cast<size_t>(tag_index) * 4;
  // Board order: corner 3 is the top-left as printed, 2 the top-right, 0 the bottom-left.
  const Eigen::Vector3d& p_TL = board_.corners()[first + 3];
  const Eigen::Vector3d across = board_.corners()[first + 2] - p_TL;
  const Eigen::Vector3d down = board_.corners()[first + 0] - p_TL;
  const double quarter_cell = 0.25 / width_;
  double sum = 0;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      const Eigen::Vector3d p_TQ =
          p_TL + (s + i * quarter_cell) * across + (t + j * quarter_cell) * down;
      Eigen::Vector2d uv;
      if (!camera.ProjectRay(X_CT * p_TQ, &uv)) return NAN;
      sum += GreyAtPredictedPixel(image32, uv);
    }
  }
  return sum / 4.0;
}

// Mean level of the white gap beside the middle of each side.
double TagCodeReader::QuietZoneLevel(const cv::Mat& image32, const CameraModel& camera,
                                     const RigidTransform& X_CT, int tag_index) const {
  const double out = quiet_offset_cells_ / width_;
  double sum = 0;
  int count = 0;
  for (double along : {0.35, 0.5, 0.65}) {
    for (const auto& [s, t] : {std::pair{along, -out}, std::pair{along, 1 + out},
                               std::pair{-out, along}, std::pair{1 + out, along}}) {
      const double level = SampleCell(image32, camera, X_CT, tag_index, s, t);
      if (std::isnan(level)) continue;  // beside the image's edge
      sum += level;
      ++count;
    }
  }
  return count > 0 ? sum / count : NAN;
}

bool TagCodeReader::InBorder(int row, int col) const {
  return std::min({row, col, width_ - 1 - row, width_ - 1 - col}) < border_cells_;
}

// The cells' levels at their centres, sharpened as libapriltag's decoder sharpens them
// (decode_sharpening): at 2 px per cell the blur leaves a lone white cell among black ones
// below the black/white midpoint, and v + k (4 v - neighbours) restores it. Cells outside
// the tag are the quiet zone's white. Empty when a cell falls outside the image.
std::vector<double> TagCodeReader::SharpenedCells(const cv::Mat& image32, const CameraModel& camera,
                                                  const RigidTransform& X_CT, int tag_index,
                                                  double white) const {
  const size_t n = static_cast<size_t>(width_);
  std::vector<double> levels(n * n);
  for (size_t k = 0; k < levels.size(); ++k) {
    levels[k] =
        SampleCell(image32, camera, X_CT, tag_index, (static_cast<double>(k % n) + 0.5) / width_,
                   (static_cast<double>(k / n) + 0.5) / width_);
    if (std::isnan(levels[k])) return {};
  }
  const auto level = [&](int row, int col) {
    const bool inside = row >= 0 && col >= 0 && row < width_ && col < width_;
    return inside ? levels[static_cast<size_t>(row * width_ + col)] : white;
  };
  std::vector<double> sharpened(levels.size());
  for (int row = 0; row < width_; ++row) {
    for (int col = 0; col < width_; ++col) {
      const double v = level(row, col);
      const double neighbours =
          level(row - 1, col) + level(row + 1, col) + level(row, col - 1) + level(row, col + 1);
      sharpened[static_cast<size_t>(row * width_ + col)] = v + sharpening_ * (4 * v - neighbours);
    }
  }
  return sharpened;
}

TagCodeReading TagCodeReader::Read(const cv::Mat& image32, const CameraModel& camera,
                                   const RigidTransform& X_CT, int tag_index) const {
  TagCodeReading reading;
  const std::vector<bool>& expected = cells_[static_cast<size_t>(tag_index)];
  const double white = QuietZoneLevel(image32, camera, X_CT, tag_index);
  if (std::isnan(white)) return {.code_errors = width_ * width_};
  const std::vector<double> levels = SharpenedCells(image32, camera, X_CT, tag_index, white);
  if (levels.empty()) return {.code_errors = width_ * width_};
  double black = 0;
  int border = 0;
  for (int row = 0; row < width_; ++row) {
    for (int col = 0; col < width_; ++col) {
      if (!InBorder(row, col)) continue;
      black += levels[static_cast<size_t>(row * width_ + col)];
      ++border;
    }
  }
  black /= std::max(border, 1);
  reading.contrast = white - black;
  const double threshold = 0.5 * (white + black);
  for (int row = 0; row < width_; ++row) {
    for (int col = 0; col < width_; ++col) {
      const size_t k = static_cast<size_t>(row * width_ + col);
      const bool reads_white = levels[k] > threshold;
      if (InBorder(row, col)) {
        reading.border_errors += reads_white ? 1 : 0;
      } else if (reads_white != expected[k]) {
        ++reading.code_errors;
      }
    }
  }
  return reading;
}

}  // namespace h4::cam
