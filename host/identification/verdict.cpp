// The verdict on an identification; see verdict.h. DecideVerdict reads top-down: the checks
// run from the case that makes every later figure meaningless (too few poses) to the one
// that needs them all (the chi-square test).
#include "host/identification/verdict.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "common/text/enum_names.h"
#include "common/text/invalid_reason.h"
#include "common/units.h"

namespace h4::host {
namespace {

struct VerdictCase {
  Verdict verdict;
  std::string text;
};

double Fraction(int part, int whole) {
  return whole > 0 ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

int Dof(const VerdictInputs& in) { return std::max(0, in.residuals - in.free_parameters); }

double ReducedChi2(const VerdictInputs& in) {
  return Dof(in) > 0 ? in.chi2 / static_cast<double>(Dof(in)) : 0.0;
}

int PosesNeeded(const VerdictInputs& in, const VerdictOptions& options) {
  const double residuals_per_pose =
      in.poses_in_fit > 0 ? static_cast<double>(in.residuals) / in.poses_in_fit : 6.0;
  return MinimumPosesInFit(in.free_parameters, residuals_per_pose, options);
}

std::optional<VerdictCase> TooFewPoses(const VerdictInputs& in, const VerdictOptions& options) {
  const int needed = PosesNeeded(in, options);
  if (in.poses_in_fit >= needed) return std::nullopt;
  return VerdictCase{
      Verdict::kTooFewPoses,
      fmt::format("Too few poses: {} in the fit, Model {} needs at least {} to identify its {} "
                  "free parameters and check the fit against the camera noise. Collect more "
                  "poses spread over the whole workspace and every orientation (the paper uses "
                  "81) and identify again.",
                  in.poses_in_fit, ToString(in.model), needed, in.free_parameters)};
}

const char* kCheckRobotYaml =
    "Check robot.yaml against the robot: lengths in metres and angles in radians, the joint "
    "order and signs (q1..q4 as the controller reports them), the joint offsets q0, and that "
    "X_BC / X_TE describe this camera and board mounting; then identify again.";

std::optional<VerdictCase> InconsistentWithApriori(const VerdictInputs& in,
                                                   const VerdictOptions& options) {
  const int total = in.poses_in_fit + in.poses_rejected;
  std::string why;
  if (Fraction(in.out_of_reach, total) > options.max_out_of_reach_fraction) {
    why = fmt::format("{} of the {} poses are out of reach of the robot", in.out_of_reach, total);
  } else if (in.position_misfit_m >= options.inconsistent_misfit_m) {
    why = fmt::format("the fitted robot still misses the measured board by {:.1f} mm RMS",
                      in.position_misfit_m * 1e3);
  } else if (in.largest_length_change > options.max_relative_length_change) {
    why = fmt::format("the fit had to change {} by {:.0f} % of its a priori value",
                      in.largest_length_parameter, 100.0 * in.largest_length_change);
  } else if (in.largest_angle_change > options.max_angle_change) {
    why = fmt::format("the fit had to turn {} by {:.1f} deg from its a priori value",
                      in.largest_angle_parameter, DegreesFromRadians(in.largest_angle_change));
  } else {
    return std::nullopt;
  }
  return VerdictCase{Verdict::kInconsistentWithApriori,
                     "The data do not match the a priori robot: " + why + ". " + kCheckRobotYaml};
}

std::optional<VerdictCase> NotIdentifiable(const VerdictInputs& in, const VerdictOptions& options) {
  std::string why;
  if (!in.converged) {
    why = "the solver did not converge";
  } else if (!in.has_covariance) {
    why = "the parameters have no covariance (the poses leave some direction unseen)";
  } else if (in.condition_number > options.max_condition_number) {
    why = fmt::format("the poses separate the parameters poorly (condition number {:.3g})",
                      in.condition_number);
  } else {
    return std::nullopt;
  }
  return VerdictCase{Verdict::kNotIdentifiable,
                     "Not identifiable: " + why +
                         ". Collect poses that span the whole workspace: the four corners at "
                         "several heights, each at the extreme rotations (the paper's grid: "
                         "X, Y over 200 mm, Z over 150 mm, theta -20, 0, 20 deg)."};
}

// The part of the board position misfit the noise model does not explain: with a reduced
// chi-square c, a share 1 / c of the squared misfit is the noise the sigmas predict.
double UnexplainedMisfit(const VerdictInputs& in) {
  const double reduced = ReducedChi2(in);
  return reduced > 1.0 ? in.position_misfit_m * std::sqrt(1.0 - 1.0 / reduced) : 0.0;
}

bool WithinNoise(const VerdictInputs& in, const VerdictOptions& options) {
  return ChiSquareUpperTail(in.chi2, Dof(in)) >= options.significance ||
         ReducedChi2(in) <= options.tolerated_reduced_chi2;
}

std::optional<VerdictCase> ModelCannotDescribe(const VerdictInputs& in,
                                               const VerdictOptions& options) {
  const double reduced = ReducedChi2(in);
  if (WithinNoise(in, options) || UnexplainedMisfit(in) < options.negligible_misfit_m) {
    return std::nullopt;
  }
  const std::string misfit = fmt::format(
      "the board poses miss the fit by {:.3f} mm RMS, {:.1f} times the variance the camera "
      "noise explains (chi-square / dof {:.3g})",
      in.position_misfit_m * 1e3, reduced, reduced);
  const std::string sigmas = in.dataset_sigmas
                                 ? ""
                                 : " The dataset carries no pose covariance: the test assumed the "
                                   "default camera noise (0.2 mm, 0.03 deg).";
  if (in.model == ModelKind::k12) {
    return VerdictCase{Verdict::kModelCannotDescribe,
                       "Model 12 cannot describe this robot: " + misfit +
                           ". Use Model 31: identify again with --model 31 --from this "
                           "result." +
                           sigmas};
  }
  return VerdictCase{Verdict::kModelCannotDescribe,
                     "Model 31 does not describe this robot within the camera noise: " + misfit +
                         ". " + kModel31MisfitAdvice + sigmas};
}

// Many outliers on a model that fits the rest within the noise: the data, not the model.
// (Checked after the chi-square test: a model that cannot describe the robot makes its
// worst-fitted poses look like outliers.)
std::optional<VerdictCase> ManyOutliers(const VerdictInputs& in, const VerdictOptions& options) {
  const int total = in.poses_in_fit + in.poses_rejected;
  if (Fraction(in.poses_rejected, total) <= options.max_rejected_fraction) return std::nullopt;
  return VerdictCase{Verdict::kInconsistentWithApriori,
                     fmt::format("The data do not match the a priori robot: {} of the {} poses "
                                 "were rejected as outliers. ",
                                 in.poses_rejected, total) +
                         kCheckRobotYaml};
}

VerdictCase Good(const VerdictInputs& in, const VerdictOptions& options) {
  const std::string optimistic =
      WithinNoise(in, options)
          ? ""
          : fmt::format(
                " The camera's pose covariance is optimistic (chi-square / dof {:.3g}): "
                "the misfit it does not explain, {:.4f} mm, is negligible, and the "
                "parameter sigmas are scaled by it.",
                ReducedChi2(in), UnexplainedMisfit(in) * 1e3);
  return {Verdict::kGood,
          fmt::format("Good: Model {} fits the {} poses {} (chi-square / dof {:.3g}, board "
                      "position misfit {:.3f} mm RMS). Export it to the controller.{}",
                      ToString(in.model), in.poses_in_fit,
                      optimistic.empty() ? "within the camera noise" : "to a negligible misfit",
                      ReducedChi2(in), in.position_misfit_m * 1e3, optimistic)};
}

std::vector<std::pair<std::string, double>> Figures(const VerdictInputs& in) {
  return {{"poses_given", in.poses_given},
          {"poses_in_fit", in.poses_in_fit},
          {"poses_rejected", in.poses_rejected},
          {"poses_out_of_reach", in.out_of_reach},
          {"free_parameters", in.free_parameters},
          {"chi2", in.chi2},
          {"dof", Dof(in)},
          {"reduced_chi2", ReducedChi2(in)},
          {"chi2_upper_tail_probability", ChiSquareUpperTail(in.chi2, Dof(in))},
          {"condition_number", in.condition_number},
          {"position_misfit_m", in.position_misfit_m},
          {"unexplained_position_misfit_m", UnexplainedMisfit(in)},
          {"largest_relative_length_change", in.largest_length_change},
          {"largest_angle_change_rad", in.largest_angle_change},
          {"dataset_sigmas", in.dataset_sigmas ? 1.0 : 0.0}};
}

}  // namespace

constexpr EnumNames<Verdict, Verdict::kNoiseOverstated> kVerdictCodes = {
    "good",          "model_cannot_describe", "inconsistent_with_apriori", "not_identifiable",
    "too_few_poses", "noise_overstated"};

int MinimumPosesInFit(int free_parameters, double residuals_per_pose,
                      const VerdictOptions& options) {
  const double for_parameters =
      options.min_residuals_per_parameter * free_parameters / std::max(1.0, residuals_per_pose);
  return std::max(options.min_poses, static_cast<int>(std::ceil(for_parameters)));
}

const char* VerdictCode(Verdict verdict) {
  return kVerdictCodes.NameOf(verdict, "not_identifiable");
}

std::optional<Verdict> ParseVerdictCode(const std::string& code) {
  return kVerdictCodes.ValueNamed(code);
}

bool VerdictOptions::IsValid(std::string* why) const {
  if (min_poses < 1) return Invalid(why, "verdict options: min_poses must be at least 1");
  if (!(min_residuals_per_parameter >= 1)) {
    return Invalid(why, "verdict options: min_residuals_per_parameter must be >= 1");
  }
  if (!(significance > 0 && significance < 1)) {
    return Invalid(why, "verdict options: significance must be in (0, 1)");
  }
  if (!(tolerated_reduced_chi2 >= 1)) {
    return Invalid(why, "verdict options: tolerated_reduced_chi2 must be >= 1");
  }
  if (!(inconsistent_misfit_m > 0)) {
    return Invalid(why, "verdict options: inconsistent_misfit_m must be positive");
  }
  if (!(max_out_of_reach_fraction >= 0 && max_out_of_reach_fraction < 1) ||
      !(max_rejected_fraction >= 0 && max_rejected_fraction < 1)) {
    return Invalid(why, "verdict options: the fractions must be in [0, 1)");
  }
  if (!(max_relative_length_change > 0) || !(max_angle_change > 0)) {
    return Invalid(why, "verdict options: the largest parameter changes must be positive");
  }
  if (!(max_condition_number > 1)) {
    return Invalid(why, "verdict options: max_condition_number must exceed 1");
  }
  if (!(negligible_misfit_m >= 0)) {
    return Invalid(why, "verdict options: negligible_misfit_m must be >= 0");
  }
  return true;
}

double ChiSquareUpperTail(double chi2, double dof) {
  if (!(dof > 0) || !(chi2 >= 0) || !std::isfinite(chi2)) return chi2 > 0 ? 0.0 : 1.0;
  const double variance = 2.0 / (9.0 * dof);
  const double z = (std::cbrt(chi2 / dof) - (1.0 - variance)) / std::sqrt(variance);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

ResultVerdict DecideVerdict(const VerdictInputs& inputs, const VerdictOptions& options,
                            Verdict* verdict) {
  std::optional<VerdictCase> decided = TooFewPoses(inputs, options);
  if (!decided) decided = InconsistentWithApriori(inputs, options);
  if (!decided) decided = NotIdentifiable(inputs, options);
  if (!decided) decided = ModelCannotDescribe(inputs, options);
  if (!decided) decided = ManyOutliers(inputs, options);
  if (!decided) decided = Good(inputs, options);
  if (verdict != nullptr) *verdict = decided->verdict;
  return {.code = VerdictCode(decided->verdict), .text = decided->text, .figures = Figures(inputs)};
}

}  // namespace h4::host
