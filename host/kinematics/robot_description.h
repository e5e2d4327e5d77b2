// The a priori description of an H4 and of its measurement set-up (robot.yaml,
// common/formats/README.md), with the parameters of Models 12 and 31 as common/README.md names
// them.
#pragma once

#include <array>
#include <optional>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"

namespace h4 {

/// Model 12, the design model (paper eq. (1)-(2)); lengths in m, angles in rad.
struct Model12Parameters {
  double h = 0.06;        ///< half-length of the nacelle's central bar, m
  double arm = 0.26;      ///< arm length (the paper's l in eq. (1)), m
  double forearm = 0.48;  ///< forearm length (the paper's L), m
  double R = 0.14;        ///< distance from base joint P_i to nacelle joint A_i0, m
  double d = 0.0;         ///< nacelle dimension d, m (no influence on Model 12)
  std::array<double, 4> alpha{0.0, 3.1416, 4.7124, 4.7124};  ///< leg directions, rad
  std::array<double, 4> q0{0.0, 0.0, 0.0, 0.0};              ///< joint offsets, rad
};

/// Model 31, the calibration model (paper eq. (4)); base frame B31 at P_1.
struct Model31Parameters {
  /// Base joint positions P_2..P_4 in B31 (P_1 = 0), m: index 0 is P_2.
  std::array<Eigen::Vector3d, 3> P{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                   Eigen::Vector3d::Zero()};
  std::array<double, 4> psi{};      ///< joint axis azimuths, rad
  std::array<double, 4> beta{};     ///< joint axis elevations, rad
  std::array<double, 4> q0{};       ///< joint offsets, rad
  std::array<double, 4> arm{};      ///< arm lengths (the paper's L_i in eq. (4)), m
  std::array<double, 4> forearm{};  ///< forearm lengths (the paper's l_i), m
  double h = 0.0;                   ///< nacelle half bar, m
  double d = 0.0;                   ///< nacelle dimension d, m
};

/// Assembly signs: s_i, the lateral bar of leg i, and eps_i, the elbow branch of eq. (2).
struct Assembly {
  std::array<int, 4> bar{1, -1, 1, -1};
  std::array<int, 4> elbow{-1, -1, -1, -1};
};

struct RobotDescription {
  Model12Parameters model12;
  /// Set when robot.yaml has a model31: block; otherwise derive it with NominalModel31.
  std::optional<Model31Parameters> model31;
  Assembly assembly;
  RigidTransform X_BC;  ///< a priori camera pose in base B
  RigidTransform X_TE;  ///< a priori end-effector pose in board frame T
};

/// The exact Model 31 equivalent of a Model 12 robot
/// (common/README.md#model-31-calibration-model-31-parameters).
Model31Parameters NominalModel31(const Model12Parameters& m12);

/// Model 31 parameters of a description: its model31 block, else NominalModel31(model12).
Model31Parameters Model31Of(const RobotDescription& robot);

}  // namespace h4
