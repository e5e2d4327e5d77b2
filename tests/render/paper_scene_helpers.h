// Test helper for the tests of rendered scenes (tests/render, and those above it that render,
// such as tests/camera_service): the paper's board and camera with what these tests build
// from them.
#pragma once

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "firmware/render/board_renderer.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {

/// The paper's board and camera, a renderer of them (default render options), the board's
/// model (its corners by id) and the camera's projection.
struct PaperScene {
  AprilGridSpec board = scenes::PaperBoard();
  CameraIntrinsics camera = scenes::PaperCamera();
  BoardRenderer renderer{board, camera, RenderOptions{}};
  BoardModel board_model{board};
  CameraModel projection{camera};
};

}  // namespace h4::cam
