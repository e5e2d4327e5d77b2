// The reference paper's published validation numbers (Renaud et al., ICRA 2003), shown side
// by side with ours when the report runs on the paper scenario (Table 2 values as truth).
#pragma once

#include <array>

namespace h4::host::paper {

/// Table 3, rad, measured minus model: before calibration, after Model 12, after Model 31.
inline constexpr std::array<double, 4> kTable3MeanBefore{9.0e-2, 3.5e-2, 7.3e-2, 8.3e-2};
inline constexpr std::array<double, 4> kTable3RmsBefore{9.0e-2, 3.7e-2, 7.4e-2, 8.3e-2};
inline constexpr std::array<double, 4> kTable3Mean12{7.1e-5, 1.1e-4, -7.7e-4, -2.1e-4};
inline constexpr std::array<double, 4> kTable3Rms12{1.4e-3, 1.3e-3, 1.4e-3, 2.6e-3};
inline constexpr std::array<double, 4> kTable3Mean31{-2.0e-4, 5.2e-4, -4.7e-4, 7.4e-5};
inline constexpr std::array<double, 4> kTable3Rms31{2.9e-3, 2.6e-3, 1.8e-3, 3.1e-3};

/// Table 4, straightness (m), directions 1 and 2.
inline constexpr std::array<double, 2> kTable4Before{1.3e-3, 2.3e-3};
inline constexpr std::array<double, 2> kTable4Model12{4.9e-4, 5.8e-4};
inline constexpr std::array<double, 2> kTable4Model31{5.9e-4, 1.1e-3};

/// Square path error, m: about 5 mm before calibration, under 0.5 mm after.
inline constexpr double kSquareBefore = 5e-3;
inline constexpr double kSquareAfter = 0.5e-3;

/// A priori positioning error: 26 mm and 0.022 rad.
inline constexpr double kAprioriPosition = 26e-3;
inline constexpr double kAprioriTheta = 0.022;

/// Rotation axis spread of the 4-DoF check, deg.
inline constexpr double kAxisSpreadDeg = 0.12;

}  // namespace h4::host::paper
