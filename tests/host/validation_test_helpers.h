// Shared fixtures of the validation and report tests: the paper's scenario (Table 2
// "Identified" as the true robot), its noise-free dataset, and an identification result
// holding the true parameters (what a perfect identification would return).
#pragma once

#include "common/formats/identification_result.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"
#include "host/validation/validation.h"

namespace h4::host {

/// The paper's true robot (placement drawn from seed 1).
SimulatedRobot PaperTruth();

/// A Model 12 result whose values are the truth's, with `valid` as held-out pose ids.
IdentificationResult PerfectModel12Result(const SimulatedRobot& truth,
                                          const std::vector<int64_t>& valid);

/// Inputs of Validate on the paper scenario: the 81-pose grid without noise, the perfect
/// Model 12 result, two ruler runs without noise, the truth.
ValidationInputs PaperValidationInputs();

}  // namespace h4::host
