// The synthetic camera: frames of a board rendered at a settable pose X_CT (the camera
// service's `--source sim`, the tests and benchmarks). The noise-free image is rendered
// when a frame is asked for, once per pose; each frame adds fresh sensor noise seeded by (seed, sequence), so a run
// is reproducible.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/render/board_renderer.h"
#include "firmware/frames/frame_source.h"

namespace h4::cam {

struct SimSourceOptions {
  /// Image formation. The default is the "clean" preset the tests' accuracy figures are
  /// stated for; `h4cam run --source sim` uses the service configuration's (by default
  /// the realistic "processed" preset, service_config.h).
  RenderOptions render;
  uint64_t seed = 1;
  double frame_rate_hz = 30.0;  ///< spacing of the synthetic timestamps
  int64_t start_utime = 0;      ///< utime of frame 0
  /// Live camera behaviour (h4cam run): frames come at frame_rate_hz in real time, stamped
  /// with the wall clock, so that they pair with the robot's joint states by utime and a
  /// robot moving during a group shows in it. Off: as fast as asked, synthetic stamps.
  bool real_time = false;
};

class SimSource final : public DevicelessFrameSource {
 public:
  SimSource(const BoardSpec& board, const CameraIntrinsics& camera, SimSourceOptions options);

  /// Places the board for the next frames (thread-safe: may be called from a message
  /// handler); std::nullopt takes it out of view.
  void SetPose(const std::optional<RigidTransform>& X_CT);
  std::optional<RigidTransform> pose() const;

  bool Open() override;
  /// A new noisy frame of the current scene; waits (up to `timeout`) only in real time.
  std::optional<Frame> Next(std::chrono::milliseconds timeout) override;
  std::string Describe() const override { return "sim"; }

 private:
  /// The noise-free image of the current pose, rendered if the pose changed since.
  cv::Mat CleanImage();

  SimSourceOptions options_;
  BoardRenderer renderer_;
  mutable std::mutex mutex_;
  std::optional<RigidTransform> X_CT_;         ///< where the board is to be seen
  std::optional<RigidTransform> clean_pose_;   ///< where it is in clean_
  cv::Mat clean_;  // CV_32F noise-free image at clean_pose_ (empty: none rendered yet)
  int64_t sequence_ = 0;
  std::optional<int64_t> last_utime_;  ///< real time: stamp of the last frame
};

}  // namespace h4::cam
