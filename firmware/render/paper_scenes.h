// Scenes like the paper's set-up, for the measuring pipeline's tests and benchmarks and
// the simulated camera: a 1024 x 768 camera
// with a 3.8 mm lens (~817 px focal length) and mild distortion, the 6 x 6 AprilTag grid
// of 30 mm tags, and board poses at 0.45-0.65 m tilted up to 25 degrees.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/render/board_renderer.h"

namespace h4::cam::scenes {

CameraIntrinsics PaperCamera();
AprilGridSpec PaperBoard();
/// A pose with the board centre near the optical axis at `depth` (m), tilted by `tilt`
/// (rad) about an axis in the board plane at angle `axis_angle`, and rolled by `roll`.
RigidTransform BoardPose(const AprilGridSpec& board, double depth, double tilt, double axis_angle,
                         double roll, double dx = 0, double dy = 0);
/// Random scene poses in the paper's range (depth 0.45-0.65 m, tilt up to 25 deg), or with
/// the board centre's depth drawn in [min_depth, max_depth] (m) instead.
std::vector<RigidTransform> RandomPoses(int count, uint64_t seed, double min_depth = 0.45,
                                        double max_depth = 0.65);
/// Scene poses whose tags' sides run along the pixel axes: the board turned by a multiple of
/// 90 deg (+-0.5) and tilted at most 2 deg, its centre's depth in [min_depth, max_depth] (m).
std::vector<RigidTransform> AxisAlignedPoses(int count, uint64_t seed, double min_depth = 0.45,
                                             double max_depth = 0.65);
/// The CV_32F mean of `frames` noisy renderings of the clean image.
cv::Mat AveragedFrames(const BoardRenderer& renderer, const cv::Mat& clean, int frames,
                       uint64_t seed);

}  // namespace h4::cam::scenes
