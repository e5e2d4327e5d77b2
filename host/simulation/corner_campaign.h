// A simulated campaign as the corner path sees it (common/README.md#identification-from-corners):
// the board's corners projected through the TRUE camera with Gaussian pixel noise, and the board
// poses a camera would report from them, solved with the camera file's (ASSUMED) intrinsics. When
// the two cameras differ, the poses carry the file's error as a real campaign does; the corners
// carry the truth.
#pragma once

#include <cstdint>
#include <vector>

#include "common/board/board_model.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/simulation/dataset_simulator.h"

namespace h4::host {

struct CornerCampaignOptions {
  double sigma_px = 0.05;  ///< per-axis corner noise, px
  double sigma_q = 2e-5;   ///< encoder noise, rad
  uint64_t seed = 1;
  int valid_count = 0;  ///< rows marked "valid", chosen by seed (dataset_simulator.h)
};

struct CornerCampaign {
  std::vector<DatasetRow> rows;            ///< X_CT solved through the assumed camera
  std::vector<CornerObservation> corners;  ///< corners inside the true image, with sigma_px
  std::vector<SimulatedPose> truth;        ///< same order as rows
};

/// Poses whose board shows fewer than 12 corners in the image, or whose pose cannot be
/// solved, are left out.
CornerCampaign SimulateCornerCampaign(const SimulatedRobot& robot, const PosePlan& plan,
                                      const BoardModel& board, const CameraIntrinsics& true_camera,
                                      const CameraIntrinsics& assumed_camera,
                                      const CornerCampaignOptions& options);

}  // namespace h4::host
