// The closed-form solution shared by both models' inverse kinematics (paper eq. (2), in
// the atan2 form of common/README.md): the leg angle phi with M cos phi + N sin phi = G.
#pragma once

namespace h4::host {

/// Solves M cos(phi) + N sin(phi) = G on the branch `elbow` (eps_i = +-1):
///   phi = atan2(N, M) + eps * acos(G / sqrt(M^2 + N^2)).
/// Returns false (and leaves *phi untouched) when there is no real solution,
/// |G| > sqrt(M^2 + N^2), or the inputs are degenerate or non-finite. A ratio exceeding 1
/// by rounding only (1e-12 relative) is clamped: the pose is on the workspace boundary.
bool SolveLegAngle(double M, double N, double G, int elbow, double* phi);

}  // namespace h4::host
