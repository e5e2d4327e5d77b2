// The closed-form solution shared by both models' inverse kinematics (paper eq. (2), in
// the atan2 form of common/README.md): the leg angle phi with M cos phi + N sin phi = G, and
// the loop over the four legs that turns each model's equation into joint angles.
#pragma once

#include <array>
#include <cstddef>

#include "common/geometry/rotation.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// Solves M cos(phi) + N sin(phi) = G on the branch `elbow` (eps_i = +-1):
///   phi = atan2(N, M) + eps * acos(G / sqrt(M^2 + N^2)).
/// Returns false (and leaves *phi untouched) when there is no real solution,
/// |G| > sqrt(M^2 + N^2), or the inputs are degenerate or non-finite. A ratio exceeding 1
/// by rounding only (1e-12 relative) is clamped: the pose is on the workspace boundary.
bool SolveLegAngle(double M, double N, double G, int elbow, double* phi);

/// One leg's closure equation at a pose in the form M cos(phi) + N sin(phi) = G.
struct LegEquation {
  double M = 0.0, N = 0.0, G = 0.0;
};

/// Both models' inverse kinematics at pose x: per leg, phi from equation_of_leg(leg) on the
/// assembly's elbow branch, then q = phi - q0 wrapped; a leg without a solution is left
/// unreachable, and a non-finite pose reaches no leg.
template <typename EquationOfLeg>
IkResult SolveLegs(const EePose& x, const Assembly& assembly, const std::array<double, 4>& q0,
                   EquationOfLeg equation_of_leg) {
  IkResult result;
  if (!x.allFinite()) return result;
  for (int leg = 0; leg < 4; ++leg) {
    const auto i = static_cast<size_t>(leg);
    const LegEquation e = equation_of_leg(leg);
    double phi = 0.0;
    if (SolveLegAngle(e.M, e.N, e.G, assembly.elbow[i], &phi)) {
      result.q[leg] = WrapAngle(phi - q0[i]);
      result.reachable[i] = true;
    }
  }
  return result;
}

}  // namespace h4::host
