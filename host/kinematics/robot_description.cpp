// Nominal Model 31 from Model 12 (common/README.md#model-31-calibration-model-31-parameters).
#include "host/kinematics/robot_description.h"

#include <cmath>
#include <numbers>

namespace h4 {

Model31Parameters NominalModel31(const Model12Parameters& m12) {
  Model31Parameters m31;
  const double R = m12.R;
  const double a1 = m12.alpha[0];
  for (int i = 1; i < 4; ++i) {
    const double ai = m12.alpha[static_cast<size_t>(i)];
    m31.P[static_cast<size_t>(i - 1)] =
        Eigen::Vector3d(R * (std::cos(a1) - std::cos(ai)), R * (std::sin(a1) - std::sin(ai)), 0.0);
  }
  for (size_t i = 0; i < 4; ++i) {
    m31.psi[i] = m12.alpha[i];
    m31.beta[i] = -std::numbers::pi / 2;
    m31.q0[i] = m12.q0[i];
    m31.arm[i] = m12.arm;
    m31.forearm[i] = m12.forearm;
  }
  m31.h = m12.h;
  m31.d = m12.d;
  return m31;
}

Model31Parameters Model31Of(const RobotDescription& robot) {
  return robot.model31 ? *robot.model31 : NominalModel31(robot.model12);
}

}  // namespace h4
