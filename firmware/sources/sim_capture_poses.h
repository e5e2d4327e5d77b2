// The board poses the sim source shows `h4cam capture` (no --sim-pose): a deterministic
// sequence a technician's intrinsics session would give, so that the intrinsics step can be
// rehearsed on the simulated camera. Frame i is tilted 15-40 deg about an axis in the board
// plane that turns by the golden angle from frame to frame (every direction of tilt soon
// seen: the focal length observable), turned up to 15 deg about the optical axis, at one of
// two depths, its centre on one cell of a 3 x 3 grid over the image (the cells visited in
// an order that reaches the corners first), as far out towards the cell's image edge as
// the whole board with part of its white border stays in the image. Pure.
#pragma once

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"

namespace h4::cam {

/// X_CT of capture frame `index` (>= 0) for `board` seen through `camera`.
RigidTransform SimCapturePose(const BoardSpec& board, const CameraIntrinsics& camera, int index);

}  // namespace h4::cam
