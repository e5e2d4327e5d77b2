// Paper-like scenes; see paper_scenes.h.
#include "firmware/render/paper_scenes.h"

#include <cmath>
#include <numbers>

#include "common/board/board_model.h"
#include "common/geometry/rotation.h"
#include "common/units.h"

namespace h4::cam::scenes {

CameraIntrinsics PaperCamera() {
  CameraIntrinsics camera = CameraIntrinsics::Pinhole(1024, 768, 817.0, 816.2, 515.3, 380.7);
  camera.distortion = Eigen::VectorXd(5);
  camera.distortion << -0.12, 0.08, 0.0004, -0.0003, -0.01;
  return camera;
}

AprilGridSpec PaperBoard() {
  AprilGridSpec board;
  board.cols = 6;
  board.rows = 6;
  board.tag_size = 0.03;
  board.tag_spacing = 0.3;                    // 9 mm gaps: the board is 0.219 m wide
  board.layout = AprilGridLayout::kH4Legacy;  // the sim camera's board (aprilgrid_6x6_30mm)
  return board;
}

RigidTransform BoardPose(const AprilGridSpec& board, double depth, double tilt, double axis_angle,
                         double roll, double dx, double dy) {
  const BoardModel model(board);
  const Eigen::Vector2d mid = 0.5 * (model.pattern_min() + model.pattern_max());
  const Eigen::Vector3d p_TM(mid.x(), mid.y(), 0.0);  // board centre in T
  const Eigen::Vector3d axis(std::cos(axis_angle), std::sin(axis_angle), 0.0);
  const Eigen::Matrix3d R_CT = So3Exp(tilt * axis) * RotZ(roll);
  // Centre of the board at (dx, dy, depth) in C.
  return {R_CT, Eigen::Vector3d(dx, dy, depth) - R_CT * p_TM};
}

std::vector<RigidTransform> RandomPoses(int count, uint64_t seed, double min_depth,
                                        double max_depth) {
  cv::RNG rng(seed);
  std::vector<RigidTransform> poses;
  const AprilGridSpec board = PaperBoard();
  for (int i = 0; i < count; ++i) {
    const double depth = rng.uniform(min_depth, max_depth);
    const double tilt = RadiansFromDegrees(rng.uniform(0.0, 25.0));
    poses.push_back(BoardPose(board, depth, tilt, rng.uniform(-std::numbers::pi, std::numbers::pi),
                              rng.uniform(-std::numbers::pi, std::numbers::pi), rng.uniform(-0.04, 0.04),
                              rng.uniform(-0.03, 0.03)));
  }
  return poses;
}

std::vector<RigidTransform> AxisAlignedPoses(int count, uint64_t seed, double min_depth,
                                             double max_depth) {
  cv::RNG rng(seed);
  const AprilGridSpec board = PaperBoard();
  std::vector<RigidTransform> poses;
  for (int i = 0; i < count; ++i) {
    const double roll = std::numbers::pi / 2 * (i % 4) + RadiansFromDegrees(rng.uniform(-0.5, 0.5));
    poses.push_back(BoardPose(board, rng.uniform(min_depth, max_depth),
                              RadiansFromDegrees(rng.uniform(0.0, 2.0)),
                              rng.uniform(-std::numbers::pi, std::numbers::pi), roll,
                              rng.uniform(-0.04, 0.04), rng.uniform(-0.03, 0.03)));
  }
  return poses;
}

cv::Mat AveragedFrames(const BoardRenderer& renderer, const cv::Mat& clean, int frames,
                       uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat sum = cv::Mat::zeros(clean.size(), CV_32F);
  for (int k = 0; k < frames; ++k) {
    cv::Mat frame32;
    renderer.Expose(clean, rng).convertTo(frame32, CV_32F);
    sum += frame32;
  }
  return sum / static_cast<double>(frames);
}

}  // namespace h4::cam::scenes
