// The one way an options struct's IsValid(std::string* why) says no: the reason goes to the
// caller when it asked for one (why may be null), and the check returns false, so that each
// rule reads `if (!rule) return Invalid(why, "what must hold");`.
#pragma once

#include <string>
#include <utility>

namespace h4 {

/// Stores `reason` in *why unless why is null; returns false.
inline bool Invalid(std::string* why, std::string reason) {
  if (why != nullptr) *why = std::move(reason);
  return false;
}

}  // namespace h4
