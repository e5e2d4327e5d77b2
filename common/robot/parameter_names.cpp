// See parameter_names.h.
#include "common/robot/parameter_names.h"

#include <algorithm>
#include <array>

namespace h4 {

bool IsPositiveLengthParameter(std::string_view name) {
  constexpr std::array<std::string_view, 12> kLengths = {
      "h",    "arm",  "forearm",  "R",        "arm1",     "arm2",
      "arm3", "arm4", "forearm1", "forearm2", "forearm3", "forearm4"};
  return std::find(kLengths.begin(), kLengths.end(), name) != kLengths.end();
}

bool IsModelAngleParameter(std::string_view name) {
  constexpr std::array<std::string_view, 4> kAnglePrefixes = {"alpha", "q0", "psi", "beta"};
  return std::any_of(kAnglePrefixes.begin(), kAnglePrefixes.end(),
                     [name](std::string_view prefix) { return name.starts_with(prefix); });
}

bool IsAngleParameter(std::string_view name) {
  if (IsModelAngleParameter(name)) return true;
  const size_t dot = name.find('.');  // X_BC.rx ... X_TE.rz
  return dot != std::string_view::npos && name.substr(dot).starts_with(".r");
}

}  // namespace h4
