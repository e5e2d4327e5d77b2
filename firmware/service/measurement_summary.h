// One line on what a measurement saw, for the camera service's log (`h4cam run`): what a
// Kalibr user looks for beside "pose 25: ok" (the tags and corners used, the fit's
// reprojection RMS, the spread between the averaged frames, the board's distance and the
// pose's stated sigmas), or why there is no pose.
#pragma once

#include <string>

#include "firmware/pose/measurement.h"

namespace h4::cam {

/// "ok: 36 tags, 144 corners, RMS 0.12 px, spread 0.03 px over 10 frames, board 0.52 m
/// away, sigma 0.004 mm / 0.0021 deg per axis"; a measurement without a pose: its status
/// and reason.
std::string MeasurementSummary(const Measurement& measurement);

}  // namespace h4::cam
