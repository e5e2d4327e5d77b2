// One simulated trial of `h4cal check` end to end (check_trial.h).
#include "host/validation/check_trial.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "common/text/invalid_reason.h"
#include "host/formats/identification_result.h"

namespace h4::host {

bool CheckTrialOptions::IsValid(std::string* why) const {
  if (calibration_plan.empty()) return Invalid(why, "calibration_plan is empty");
  if (check_plan.empty()) return Invalid(why, "check_plan is empty");
  if (!(drift_sigmas >= 0.0)) return Invalid(why, "drift_sigmas must be >= 0");
  if (stated_noise && !(stated_noise->sigma_t > 0.0 && stated_noise->sigma_r > 0.0)) {
    return Invalid(why, "stated_noise sigmas must be positive");
  }
  return check.IsValid(why);
}

namespace {

// A change of one joint's offset (a motor swapped, an encoder slipped after a crash).
SimulatedRobot WithJointOffsetMoved(SimulatedRobot robot, int joint, double change) {
  const auto k = static_cast<size_t>(joint);
  if (robot.model31) {
    robot.model31->q0[k] += change;
  } else {
    robot.model12.q0[k] += change;
  }
  return robot;
}

// The sigmas the rows state: the stated noise's, else the noise's own.
const NoiseOptions& StatedNoise(const CheckTrialOptions& options) {
  return options.stated_noise ? *options.stated_noise : options.noise;
}

std::vector<DatasetRow> WithStatedSigmas(std::vector<DatasetRow> rows, const NoiseOptions& stated) {
  for (DatasetRow& row : rows) {
    row.sigma_t = stated.sigma_t;
    row.sigma_r = stated.sigma_r;
  }
  return rows;
}

// A campaign's rows: the options' noise, the camera's stated sigmas.
std::vector<DatasetRow> SimulateRows(const SimulatedRobot& robot, const PosePlan& plan,
                                     const CheckTrialOptions& trial, uint64_t seed) {
  DatasetOptions options;
  options.noise = trial.noise;
  options.seed = seed;
  options.valid_count = 0;
  return WithStatedSigmas(SimulateDataset(robot, plan, options).rows, StatedNoise(trial));
}

// The noise-free check rows, with the sigmas the noisy ones carry (the check's weights).
std::vector<DatasetRow> NoiseFreeRows(const SimulatedRobot& robot, const PosePlan& plan,
                                      const CheckTrialOptions& trial) {
  DatasetOptions options;
  options.noise = NoiseOptions::None();
  options.valid_count = 0;
  return WithStatedSigmas(SimulateDataset(robot, plan, options).rows, StatedNoise(trial));
}

// `h4cal identify` twice, as the demo on the grid: Model 12, then Model 31 from it; the
// result read back from its JSON text, so the check sees what the file keeps.
std::optional<IdentificationResult> IdentifyAsTheCliDoes(const RobotDescription& apriori,
                                                         const std::vector<DatasetRow>& rows,
                                                         const IdentificationOptions& options) {
  const auto [model12, model31] = IdentifyModel12Then31(apriori, rows, options);
  if (!model12.summary.usable || !model31.summary.usable) return std::nullopt;
  return ParseIdentificationResult(FormatIdentificationResult(model31.result), "trial.json");
}

// The joint offset change (rad, > 0) that moves the noise-free board by `sigmas` of the
// check's predicted error (RMS Mahalanobis over the poses), from a small probe change.
double JointOffsetChangeFor(double sigmas, const IdentificationResult& result,
                            const Assembly& assembly, const SimulatedRobot& truth, int joint,
                            const CheckTrialOptions& options) {
  constexpr double kProbe = 1e-5;  // rad: far below 3 sigma, far above rounding
  const DriftCheckResult before = CheckResultForDrift(
      result, assembly, NoiseFreeRows(truth, options.check_plan, options), options.check);
  const DriftCheckResult after = CheckResultForDrift(
      result, assembly,
      NoiseFreeRows(WithJointOffsetMoved(truth, joint, kProbe), options.check_plan, options),
      options.check);
  if (!before.evaluable || !after.evaluable || before.poses.size() != after.poses.size()) {
    return NAN;
  }
  double sum = 0.0;
  for (size_t j = 0; j < before.poses.size(); ++j) {
    const Eigen::Matrix<double, 6, 1> shift = after.poses[j].error - before.poses[j].error;
    sum += shift.dot(before.poses[j].predicted_covariance.ldlt().solve(shift));
  }
  const double rms_sigmas = std::sqrt(sum / static_cast<double>(before.poses.size()));
  return rms_sigmas > 0.0 ? kProbe * sigmas / rms_sigmas : NAN;
}

}  // namespace

CheckTrialOutcome RunCheckTrial(const RobotDescription& apriori, const SimulatedRobot& truth,
                                uint64_t seed, const CheckTrialOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("check trial: " + why);
  CheckTrialOutcome outcome;
  const std::optional<IdentificationResult> result =
      IdentifyAsTheCliDoes(apriori, SimulateRows(truth, options.calibration_plan, options, seed),
                           options.identification);
  if (!result) {
    outcome.message = "identification unusable";
    return outcome;
  }
  outcome.drifted_joint = static_cast<int>(seed % 4);
  const double sign = (seed / 4) % 2 == 0 ? 1.0 : -1.0;
  outcome.joint_offset_change =
      sign * JointOffsetChangeFor(options.drift_sigmas, *result, apriori.assembly, truth,
                                  outcome.drifted_joint, options);
  if (!std::isfinite(outcome.joint_offset_change)) {
    outcome.message = "check poses not evaluable on the result";
    return outcome;
  }
  outcome.identified = true;
  // Fresh noise for the verification campaigns, independent of the calibration's.
  const uint64_t check_seed = seed + 1000003;
  // The drift is sized with the full covariance; the check may see the sigmas alone.
  IdentificationResult checked = *result;
  if (options.without_covariance) checked.parameter_covariance.reset();
  const bool camera_floor = !options.stated_camera_covariance;
  outcome.unchanged = CheckResultForDrift(
      checked, apriori.assembly, SimulateRows(truth, options.check_plan, options, check_seed),
      options.check, true, camera_floor);
  const SimulatedRobot drifted =
      WithJointOffsetMoved(truth, outcome.drifted_joint, outcome.joint_offset_change);
  outcome.drifted = CheckResultForDrift(
      checked, apriori.assembly, SimulateRows(drifted, options.check_plan, options, check_seed + 1),
      options.check, true, camera_floor);
  return outcome;
}

}  // namespace h4::host
