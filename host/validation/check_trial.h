// One simulated trial of `h4cal check` end to end, to measure how often it is right: a
// calibration campaign is simulated on a true robot and identified as `h4cal identify`
// does (Model 12, then Model 31 from it), the result goes through its JSON file format,
// and a short verification campaign is simulated twice, on the unchanged robot and on the
// robot after a drift (one joint offset moved), then checked against the result
// (drift_check.h). The drift is sized by the result's own uncertainty: it moves the
// noise-free board by `drift_sigmas` of the check's predicted error (S = I + J C J^T), RMS
// over the check poses of the Mahalanobis distance, so "3 sigma" means what the result
// says it can tell apart.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "host/identification/identification.h"
#include "host/validation/drift_check.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

struct CheckTrialOptions {
  PosePlan calibration_plan;             ///< the campaign identified (poses in B)
  PosePlan check_plan;                   ///< the verification campaign (poses in B)
  double drift_sigmas = 3.0;             ///< size of the drift, in predicted sigmas (see above)
  IdentificationOptions identification;  ///< `h4cal identify`'s defaults
  DriftCheckOptions check;               ///< `h4cal check`'s defaults
  NoiseOptions noise;                    ///< `h4cal simulate`'s noise
  /// The sigmas the camera states (the rows' sigma_t, sigma_r) when they are not the noise's:
  /// smaller ones model a camera whose pose covariance is optimistic, as a rendered or real
  /// camera's covariance from its corner noise alone is. Absent: the noise's own.
  std::optional<NoiseOptions> stated_noise;
  /// Check against the stated covariance, ignoring the result's camera_error_floor.
  bool stated_camera_covariance = false;
  /// Check as against a result written before `parameter_covariance` (its sigmas alone):
  /// to measure what the covariance adds.
  bool without_covariance = false;

  bool IsValid(std::string* why) const;
};

struct CheckTrialOutcome {
  bool identified = false;           ///< false: the identification was unusable (no verdicts)
  int drifted_joint = 0;             ///< 0..3: the joint whose offset moved
  double joint_offset_change = 0.0;  ///< rad, signed
  /// The check on the unchanged robot (`drift` there is a false alarm) and on the drifted
  /// robot (`drift` there is right).
  DriftCheckResult unchanged, drifted;
  std::string message;  ///< why a trial could not be run
};

/// Runs one trial; `seed` sets the calibration noise, the check noise, the drifted joint and
/// its sign. The apriori is what the identification starts from; truth is the robot. Throws
/// std::invalid_argument on invalid options.
CheckTrialOutcome RunCheckTrial(const RobotDescription& apriori, const SimulatedRobot& truth,
                                uint64_t seed, const CheckTrialOptions& options);

}  // namespace h4::host
