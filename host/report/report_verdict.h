// The report's first section: the verdict of each identification result (what a
// technician acts on), the figures that decided it, the poses rejected with their scores
// and reasons, and which h4cal version made the result, when, from which files.
#pragma once

#include <string>

#include "host/validation/validation.h"

namespace h4::host {

/// The HTML fragment of the verdict section, for every result in `in`.
std::string VerdictSection(const ValidationInputs& in);

}  // namespace h4::host
