// A board corner seen in an image: the detector's output and the pose estimator's input.
#pragma once

#include <Eigen/Core>

namespace h4::cam {

struct CornerObservation {
  int id = -1;                                     ///< BoardModel corner id
  Eigen::Vector3d p_TQ = Eigen::Vector3d::Zero();  ///< position on the board (frame T), m
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();    ///< pixel, OpenCV convention
};

}  // namespace h4::cam
