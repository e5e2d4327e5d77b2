// The verdict's figures at a solution; see verdict_inputs.h.
#include "host/identification/verdict_inputs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "host/identification/identified_robot.h"
#include "host/kinematics/model_parameters.h"

namespace h4::host {
namespace {

// The largest relative length change and angle change of the kinematic parameters.
void FillDepartures(const SolutionToJudge& s, VerdictInputs* in) {
  for (int k = 0; k < s.p.kinematic_count(); ++k) {
    const std::string& name = s.p.names()[static_cast<size_t>(k)];
    const double before = s.apriori.values()[k];
    const double change = std::abs(s.p.values()[k] - before);
    if (IsPositiveLengthParameter(name) && before > 0 &&
        change / before > in->largest_length_change) {
      in->largest_length_change = change / before;
      in->largest_length_parameter = name;
    } else if (IsModelAngleParameter(name) && change > in->largest_angle_change) {
      in->largest_angle_change = change;
      in->largest_angle_parameter = name;
    }
  }
}

// Calibration poses the robot of `p` cannot reach (IK of the measured pose) or whose
// forward kinematics fails, and the RMS board position misfit over the others.
int OutOfReach(const KinematicModel& model, const ParameterVector& p,
               const std::vector<DatasetRow>& rows, double* position_misfit_m) {
  std::unique_ptr<KinematicModel> robot = model.Clone();
  p.ApplyTo(robot.get());
  int unreachable = 0;
  JointResidualRms(*robot, p.X_BC(), p.X_TE(), rows, &unreachable);
  const BoardPoseErrors errors = BoardPoseErrorsOf(*robot, p.X_BC(), p.X_TE(), rows);
  if (position_misfit_m != nullptr) *position_misfit_m = errors.position_rms;
  return std::max(unreachable, errors.failed);
}

// The measurement-space chi-square on the poses in the fit: residuals divided by each
// pose's sigmas (the dataset's, else the defaults).
void FillChiSquare(const SolutionToJudge& s, VerdictInputs* in) {
  IdentificationCost measurement(CostKind::kMeasurement, s.model, s.in_fit, s.cost);
  in->residuals = measurement.residual_count();
  Eigen::VectorXd r;
  if (measurement.Evaluate(s.p, &r, nullptr)) {
    in->chi2 = r.squaredNorm();
  } else {
    in->converged = false;  // some pose cannot be evaluated at the solution
  }
}

}  // namespace

VerdictInputs GatherVerdictInputs(const SolutionToJudge& s) {
  VerdictInputs in;
  in.model = s.model.kind();
  in.poses_given = s.poses_given;
  in.poses_in_fit = static_cast<int>(s.in_fit.size());
  in.poses_rejected = s.poses_rejected;
  in.free_parameters = s.p.free_count();
  in.converged = s.converged;
  in.has_covariance = s.uncertainty.ok;
  in.condition_number = s.uncertainty.condition_number;
  in.dataset_sigmas =
      s.cost.use_dataset_sigmas && std::any_of(s.in_fit.begin(), s.in_fit.end(),
                                               [](const auto& r) { return r.sigma_t.has_value(); });
  // At the solution only: a rough a priori may leave poses out of reach that the fit brings
  // in (the implicit warm-up stage is there for that).
  in.out_of_reach = OutOfReach(s.model, s.p, s.in_fit, &in.position_misfit_m);
  FillDepartures(s, &in);
  FillChiSquare(s, &in);
  return in;
}

}  // namespace h4::host
