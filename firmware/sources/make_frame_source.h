// The frame source a FrameSourceSpec names (frame_source_spec.h), made in this one place
// for `h4cam run` and `h4cam capture`/`preview`, from what each kind is made of.
#pragma once

#include <memory>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "firmware/frames/frame_source.h"
#include "firmware/sources/frame_source_spec.h"
#include "firmware/sources/libcamera_source.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {

/// What the kinds of frame source are made of; each kind reads only its own part.
struct FrameSourceParts {
  LibcameraSourceOptions libcamera;  ///< libcamera
  /// sim: the board rendered and the camera it is rendered through (the true camera,
  /// which the one a measurement assumes may differ from); both must outlive the call.
  const BoardSpec* board = nullptr;
  const CameraIntrinsics* rendered_camera = nullptr;
  SimSourceOptions sim;  ///< sim: image formation, frame rate, real time
};

/// The source `spec` names, not opened. A sim source shows no board until given a pose
/// (SimSource::SetPose). Throws std::invalid_argument for a sim spec without a board or
/// camera in `parts`.
std::unique_ptr<FrameSource> MakeFrameSource(const FrameSourceSpec& spec,
                                             const FrameSourceParts& parts);

}  // namespace h4::cam
