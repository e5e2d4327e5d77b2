// Numerical forward kinematics (Newton with step control and backtracking on the closure
// equations of eq. (1) / (4)); see forward_kinematics.h.
#include "host/kinematics/forward_kinematics.h"

#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "common/geometry/rotation.h"
#include "common/text/enum_names.h"

namespace h4::host {
namespace {

// J_f_x is rank-deficient below this reciprocal condition number (its columns are m and
// m^2/rad scaled, ~1 and ~0.05).
constexpr double kSingularRcond = 1e-12;

struct Attempt {
  FkStatus status;
  EePose x;
  int iterations;
  double residual;
  const char* reason;
};

// Newton from x0 with the step scaled to options.max_step and halved until |f| decreases.
Attempt Solve(const KinematicModel& model, const JointVector& q, const EePose& x0,
              const FkOptions& options) {
  EePose x = x0;
  Eigen::Vector4d f = model.Constraints(q, x);
  double residual = f.cwiseAbs().maxCoeff();
  Eigen::Matrix4d J_f_x;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (residual < options.residual_tolerance) {
      return {FkStatus::kConverged, x, iteration, residual, ""};
    }
    model.ConstraintJacobians(q, x, &J_f_x, nullptr, nullptr);
    const Eigen::PartialPivLU<Eigen::Matrix4d> lu(J_f_x);
    Eigen::Vector4d dx;
    if (lu.rcond() > kSingularRcond) {
      dx = -lu.solve(f);
    } else {
      // Near a singularity: a damped (Levenberg) step still decreases |f|.
      const double damping = 1e-6 * (1.0 + J_f_x.squaredNorm());
      const Eigen::Matrix4d normal =
          J_f_x.transpose() * J_f_x + damping * Eigen::Matrix4d::Identity();
      dx = -normal.ldlt().solve(J_f_x.transpose() * f);
      if (!dx.allFinite()) return {FkStatus::kSingular, x, iteration, residual, "J_f_x singular"};
    }
    const double length = dx.norm();
    if (length > options.max_step) dx *= options.max_step / length;
    const double merit = f.squaredNorm();
    double t = 1.0;
    bool decreased = false;
    for (int halving = 0; halving < 30; ++halving, t *= 0.5) {
      const EePose x_trial = x + t * dx;
      const Eigen::Vector4d f_trial = model.Constraints(q, x_trial);
      if (f_trial.allFinite() && f_trial.squaredNorm() < merit) {
        x = x_trial;
        f = f_trial;
        decreased = true;
        break;
      }
    }
    residual = f.cwiseAbs().maxCoeff();
    if (!decreased) {
      const bool at_root = residual < 100.0 * options.residual_tolerance;
      return {at_root ? FkStatus::kConverged : FkStatus::kNotConverged, x, iteration + 1, residual,
              "line search stalled: the joints admit no pose near this start"};
    }
  }
  if (residual < options.residual_tolerance) {
    return {FkStatus::kConverged, x, options.max_iterations, residual, ""};
  }
  return {FkStatus::kNotConverged, x, options.max_iterations, residual, "iteration limit reached"};
}

// True when the closed-form IK of x, on the model's assembly branch, gives q.
bool SameBranch(const KinematicModel& model, const JointVector& q, const EePose& x,
                double tolerance) {
  const IkResult ik = model.InverseKinematics(x);
  if (!ik.ok()) return false;
  for (int i = 0; i < 4; ++i) {
    if (std::abs(WrapAngle(ik.q[i] - q[i])) > tolerance) return false;
  }
  return true;
}

}  // namespace

constexpr EnumNames<FkStatus, FkStatus::kInvalidInput> kFkStatusNames = {
    "converged", "not converged", "singular", "wrong branch", "invalid input"};

const char* ToString(FkStatus status) { return kFkStatusNames.NameOf(status, "unknown"); }

FkResult ForwardKinematics(const KinematicModel& model, const JointVector& q,
                           const std::optional<EePose>& initial_guess, const FkOptions& options) {
  FkResult result;
  const EePose centre = model.WorkspaceCentre();
  if (!q.allFinite() || (initial_guess && !initial_guess->allFinite())) {
    result.status = FkStatus::kInvalidInput;
    result.x = centre;
    result.message = "forward kinematics: joints or initial guess not finite";
    return result;
  }
  EePose starts[2] = {initial_guess ? *initial_guess : centre, centre};
  const int start_count = (initial_guess && options.retry_from_centre) ? 2 : 1;
  Attempt attempt{};
  for (int k = 0; k < start_count; ++k) {
    attempt = Solve(model, q, starts[k], options);
    result.iterations += attempt.iterations;
    if (attempt.status == FkStatus::kConverged &&
        !SameBranch(model, q, attempt.x, options.branch_tolerance)) {
      attempt.status = FkStatus::kWrongBranch;
      attempt.reason = "converged to another assembly mode: IK of the pose gives other joints";
    }
    if (attempt.status == FkStatus::kConverged) break;
  }
  result.status = attempt.status;
  result.x = attempt.x.allFinite() ? attempt.x : centre;
  result.residual = std::isfinite(attempt.residual) ? attempt.residual : HUGE_VAL;
  if (!result.ok()) {
    result.message = fmt::format(
        "forward kinematics {} for q = ({:.6f}, {:.6f}, {:.6f}, {:.6f}) rad: {} (residual "
        "{:.3g} m^2 after {} iterations)",
        ToString(result.status), q[0], q[1], q[2], q[3], attempt.reason, result.residual,
        result.iterations);
  }
  return result;
}

bool ForwardKinematicsJacobians(const KinematicModel& model, const JointVector& q, const EePose& x,
                                Eigen::Matrix4d* J_x_q, Eigen::MatrixXd* J_x_xi) {
  Eigen::Matrix4d J_f_x;
  Eigen::Vector4d J_f_q;
  Eigen::MatrixXd J_f_xi;
  model.ConstraintJacobians(q, x, &J_f_x, &J_f_q, J_x_xi != nullptr ? &J_f_xi : nullptr);
  const Eigen::PartialPivLU<Eigen::Matrix4d> lu(J_f_x);
  if (!(lu.rcond() > kSingularRcond)) return false;
  if (J_x_q != nullptr) *J_x_q = -lu.solve(Eigen::Matrix4d(J_f_q.asDiagonal()));
  if (J_x_xi != nullptr) *J_x_xi = -lu.solve(J_f_xi);
  return true;
}

}  // namespace h4::host
