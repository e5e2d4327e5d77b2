// Angle unit conversions, the one place they are written. The code is in SI (rad); degrees
// exist only where people read or type them (names ending in _deg, printed figures).
#pragma once

#include <cmath>
#include <numbers>

namespace h4 {

/// deg -> rad, as deg * pi / 180.
constexpr double RadiansFromDegrees(double degrees) { return degrees * std::numbers::pi / 180.0; }

/// rad -> deg, as rad * (180 / pi).
constexpr double DegreesFromRadians(double radians) { return radians * (180.0 / std::numbers::pi); }

/// A designed position (a grid step, a square's point), m, to the nearest nanometre: a
/// thousandth of any robot's resolution, and the file says -0.15, not the sum's rounding
/// error -0.15000000000000002.
inline double DesignedMetres(double metres) { return std::round(metres * 1e9) / 1e9; }

}  // namespace h4
