// Angle unit conversions, the one place they are written. The code is in SI (rad); degrees
// exist only where people read or type them (names ending in _deg, printed figures).
#pragma once

#include <numbers>

namespace h4 {

/// deg -> rad, as deg * pi / 180.
constexpr double RadiansFromDegrees(double degrees) { return degrees * std::numbers::pi / 180.0; }

/// rad -> deg, as rad * (180 / pi).
constexpr double DegreesFromRadians(double radians) { return radians * (180.0 / std::numbers::pi); }

}  // namespace h4
