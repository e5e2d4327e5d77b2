// Shared fixtures of the validation and report tests: the paper's scenario (Table 2
// "Identified" as the true robot), its noise-free dataset, an identification result
// holding the true parameters (what a perfect identification would return), and square runs
// as a noise-free camera would measure them.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "host/formats/identification_result.h"
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

/// PaperValidationInputs as `identify` leaves them by default: every pose in the fit (no
/// `set` column, the result's calib_poses every pose, no valid_poses) and the held-out
/// figures from 10-fold cross-validation (board position 1.8734 mm, rotation 0.1203 deg RMS).
ValidationInputs EveryPoseInTheFit();

/// The default square (SquareOptions{}) as `h4cal square-plan` writes it, ids from 1001.
SquarePlan DefaultSquarePlan();

/// What the camera sees when `controller` drives the true robot through `plan` with the
/// Model 12 IK control law: a dataset row per plan point (same pose id) holding the true
/// board pose X_CT = inv(X_BC) * X_BE * inv(X_TE), noise-free, and the commanded joints.
std::vector<DatasetRow> CameraSeesSquare(const KinematicModel& controller,
                                         const SimulatedRobot& truth, const SquarePlan& plan);

/// `in` (with a truth) plus the default plan and two measured runs: "a priori" (in.apriori's
/// Model 12 as controller) and "Model 12" (the truth's Model 12 as controller).
ValidationInputs WithMeasuredSquares(ValidationInputs in);

/// Success when Validate(in) refuses the inputs with std::invalid_argument whose message
/// contains `expected`.
::testing::AssertionResult ValidateRefuses(const ValidationInputs& in, const std::string& expected);

}  // namespace h4::host
