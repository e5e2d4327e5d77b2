// Closed-form leg angle of eq. (2); see leg_angle.h.
#include "host/kinematics/leg_angle.h"

#include <algorithm>
#include <cmath>

namespace h4::host {

bool SolveLegAngle(double M, double N, double G, int elbow, double* phi) {
  const double r = std::hypot(M, N);
  if (!std::isfinite(r) || !std::isfinite(G) || r == 0.0) return false;
  double ratio = G / r;
  constexpr double kRoundingSlack = 1e-12;
  if (std::abs(ratio) > 1.0 + kRoundingSlack) return false;
  ratio = std::clamp(ratio, -1.0, 1.0);
  *phi = std::atan2(N, M) + (elbow >= 0 ? 1.0 : -1.0) * std::acos(ratio);
  return true;
}

}  // namespace h4::host
