// The parts of kinematic_model.h that are not the models' own; see kinematic_model.h.
#include "host/kinematics/kinematic_model.h"

#include <vector>

#include <fmt/format.h>

namespace h4::host {

std::string IkResult::UnreachableLegNumbers() const {
  std::vector<int> legs;
  for (size_t i = 0; i < reachable.size(); ++i) {
    if (!reachable[i]) legs.push_back(static_cast<int>(i) + 1);
  }
  return fmt::format("{}", fmt::join(legs, ", "));
}

}  // namespace h4::host
