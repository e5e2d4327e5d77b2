// The corner path's checks at its entry (issue 42, defect 9): what a corners CSV may hold
// for the camera it was measured with before a fit sees it, and what the fit's corner
// chi-square says of the corners' sigma. One corner at u = 999999 px (inside the CSV's
// bound) or one pose whose corners sat on one pixel wrecked the fit (psi2 = 7.6 rad, x2 =
// -55 km, a result h4cal's own reader refused), and a pose with every corner off the image
// was reported as another pose's forward-kinematics failure; corners with sigma_px 100 gave
// `good` at chi-square/dof 2e-5. Kept apart from corner_identification.cpp, the fit itself.
#pragma once

#include <string>
#include <vector>

#include "common/camera/board_pose_fit.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/identification/verdict.h"

namespace h4::host {

/// How far outside the camera's image a detected corner may lie, px: sub-pixel refinement
/// of a corner on the border, never more. Beyond it the corner is not of this camera.
inline constexpr double kCornerImageMarginPx = 8.0;

/// Throws std::invalid_argument naming the pose when a corner of one of `rows` lies outside
/// the camera's image (width x height, + kCornerImageMarginPx), and naming it as such when
/// every corner of the pose is off the image (another camera's corners, or another image size).
void RequireCornersInImage(const std::vector<DatasetRow>& rows,
                           const std::vector<CornerObservation>& corners,
                           const CameraIntrinsics& camera);

/// The least spread of a pose's corners, px: the square root of the smaller eigenvalue of
/// their pixel covariance. Below it the corners sit on one pixel or along one line, and no
/// board pose follows from them.
inline constexpr double kMinCornerSpreadPx = 2.0;

/// Empties the corners of each pose whose corners are degenerate (spread below
/// kMinCornerSpreadPx), so that the fit leaves the pose out; returns one reason per pose,
/// naming it.
std::vector<std::string> DropDegenerateCornerPoses(const std::vector<DatasetRow>& rows,
                                                   std::vector<PoseCorners>* grouped);

/// Below this corner chi-square per degree of freedom the corners' sigma_px is overstated
/// (by over 4.5 times): the chi-square test cannot see a misfit, and the verdict says so.
inline constexpr double kOverstatedCornerChi2PerDof = 0.05;

/// When `corner_chi2_per_dof` (the corner fit's) is below kOverstatedCornerChi2PerDof, the
/// verdict (an IdentificationOutcome's `verdict` and its result's) becomes noise_overstated
/// with the figure, whatever it was; true then.
bool FlagOverstatedCornerNoise(double corner_chi2_per_dof, Verdict* verdict,
                               IdentificationResult* result);

}  // namespace h4::host
