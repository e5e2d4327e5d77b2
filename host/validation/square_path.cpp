// The square path under the Model 12 IK control law (see square_path.h).
#include "host/validation/square_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {

std::string SquareOptions::Problem() const {
  if (!(side > 0.0) || !std::isfinite(side))
    return fmt::format("square side {} m must be > 0", side);
  if (points_per_side < 2) return "a square side needs at least 2 points";
  if (!centre.allFinite() || !std::isfinite(theta)) return "square centre or angle not finite";
  return "";
}

namespace {

// Distance from p to the line through a and b.
double DistanceToLine(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b) {
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d v = p - a;
  return (v - v.dot(u) * u).norm();
}

}  // namespace

SquareRun RunSquare(const KinematicModel& controller, const TrueRobotView& truth,
                    const SquareOptions& options) {
  if (const std::string problem = options.Problem(); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  const double half = 0.5 * options.side;
  const std::array<Eigen::Vector3d, 4> corners = {
      options.centre + Eigen::Vector3d(-half, -half, 0.0),
      options.centre + Eigen::Vector3d(half, -half, 0.0),
      options.centre + Eigen::Vector3d(half, half, 0.0),
      options.centre + Eigen::Vector3d(-half, half, 0.0)};
  const RigidTransform X_BModel = truth.X_ModelB.inverse();
  SquareRun run;
  std::optional<EePose> guess;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector3d& a = corners[side];
    const Eigen::Vector3d& b = corners[(side + 1) % 4];
    for (int k = 0; k < options.points_per_side; ++k) {
      const double s = static_cast<double>(k) / (options.points_per_side - 1);
      const Eigen::Vector3d target = a + s * (b - a);
      const EePose x_target(target[0], target[1], target[2], options.theta);
      // The control law: joints from the controller's inverse kinematics.
      const IkResult ik = controller.InverseKinematics(x_target);
      if (!ik.ok()) {
        throw std::invalid_argument(fmt::format(
            "square of side {:.0f} mm: point ({:.1f}, {:.1f}, {:.1f}) mm on side {} is out of "
            "the controller's reach (inverse kinematics has no solution)",
            options.side * 1e3, target[0] * 1e3, target[1] * 1e3, target[2] * 1e3, side + 1));
      }
      // Where the true robot goes with those joints.
      const EePose x_true_guess =
          guess ? *guess : EePoseFromTransform(truth.X_ModelB * TransformFromEePose(x_target));
      const FkResult fk = ForwardKinematics(*truth.model, ik.q, x_true_guess);
      if (!fk.ok()) {
        throw std::invalid_argument(fmt::format(
            "square of side {:.0f} mm: the true robot has no pose for the joints commanded at "
            "({:.1f}, {:.1f}, {:.1f}) mm on side {} ({})",
            options.side * 1e3, target[0] * 1e3, target[1] * 1e3, target[2] * 1e3, side + 1,
            fk.message));
      }
      guess = fk.x;
      run.commanded.push_back(target);
      run.reached.push_back(X_BModel * Eigen::Vector3d(fk.x.head<3>()));
    }
  }
  // The shape error removes the mean offset: a camera that watches the path sees the
  // square's shape, and a constant offset is the placement of the whole square.
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < run.reached.size(); ++k) offset += run.reached[k] - run.commanded[k];
  offset /= static_cast<double>(run.reached.size());
  run.offset = offset;
  double total_sq = 0.0, total_shape_sq = 0.0, total_err = 0.0;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector3d& a = corners[side];
    const Eigen::Vector3d& b = corners[(side + 1) % 4];
    SquareSideError& e = run.sides[side];
    double sum_sq = 0.0, sum_shape_sq = 0.0, sum_err = 0.0;
    for (int k = 0; k < options.points_per_side; ++k) {
      const size_t j = static_cast<size_t>(side * options.points_per_side + k);
      const double d = DistanceToLine(run.reached[j], a, b);
      const double d_shape = DistanceToLine(run.reached[j] - offset, a, b);
      sum_sq += d * d;
      sum_shape_sq += d_shape * d_shape;
      e.max = std::max(e.max, d);
      e.shape_max = std::max(e.shape_max, d_shape);
      sum_err += (run.reached[j] - run.commanded[j]).norm();
    }
    e.rms = std::sqrt(sum_sq / options.points_per_side);
    e.shape_rms = std::sqrt(sum_shape_sq / options.points_per_side);
    e.mean_position_error = sum_err / options.points_per_side;
    total_sq += sum_sq;
    total_shape_sq += sum_shape_sq;
    total_err += sum_err;
  }
  const double n = static_cast<double>(run.reached.size());
  run.rms = std::sqrt(total_sq / n);
  run.shape_rms = std::sqrt(total_shape_sq / n);
  run.mean_position_error = total_err / n;
  return run;
}

}  // namespace h4::host
