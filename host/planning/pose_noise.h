// The camera noise of a planned pose as the camera will produce it: the board pose solved
// from its corners, each with `sigma_px` pixel noise, has a covariance that depends on the
// pose (depth, tilt, where the board falls in the image). Its per-axis sigmas, as a camera
// module writes them in the dataset's sigma columns (host/simulation/corner_campaign.h does
// the same), weight the pose's information instead of one constant for every pose.
#pragma once

#include <vector>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

struct PoseSigma {
  double t = 0.0;  ///< translation std of X_CT, m (RMS over the three axes)
  double r = 0.0;  ///< rotation std of X_CT, rad (RMS over the three axes)
};

/// For each pose (in B) of `robot`'s placement: the sigmas of the board pose fitted to its
/// corners in the image with `sigma_px` noise (first order, (J^T J)^-1 at the exact pose);
/// `fallback` where fewer than 12 corners are in the image or the fit fails.
std::vector<PoseSigma> PoseSigmasFromCorners(const RobotDescription& robot,
                                             const CameraModel& camera, const BoardModel& board,
                                             const std::vector<EePose>& poses_B, double sigma_px,
                                             const PoseSigma& fallback);

}  // namespace h4::host
