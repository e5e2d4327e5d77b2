// The report's camera section (common/README.md#the-camera-files-uncertainty): the
// intrinsics the corner path refined beside the camera file's, with their sigmas; where the
// camera model misfits the corners (a residual map over the image, after mrcal's); and what
// the camera model contributes to the accuracy map.
#pragma once

#include <string>

#include "host/validation/validation.h"

namespace h4::host {

/// Per result with a `camera` key: each intrinsic's file value, refined value, their
/// difference and its sigma, or why it was kept. Empty when no result has one.
std::string RefinedIntrinsicsTable(const ValidationInputs& in);

/// Per identified model whose result gives `parameter_covariance_camera_exact`: the
/// accuracy map's median and largest sigma, the same with exact intrinsics, and the camera
/// model's share (per pose, the root of the difference of the variances). Empty when none.
std::string CameraShareTable(const ValidationReport& report);

/// The residual map's figures in words: corners, RMS over the image, inside and outside
/// half the half-diagonal, the largest cell mean.
std::string CornerResidualSummary(const CornerResidualMap& map);

}  // namespace h4::host
