// The square path under the Model 12 IK control law (see square_path.h): the point
// generator, the true robot's path, and the side errors shared with the measured path.
#include "host/validation/square_path.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/units.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {

std::string SquareOptions::Problem() const {
  if (!(side > 0.0) || !std::isfinite(side))
    return fmt::format("square side {} m must be > 0", side);
  if (points_per_side < 2)
    return fmt::format("a square side needs at least 2 points (both corners), not {}",
                       points_per_side);
  if (!centre.allFinite() || !std::isfinite(theta)) return "square centre or angle not finite";
  return "";
}

std::vector<SquarePoint> SquarePoints(const SquareOptions& options) {
  if (const std::string problem = options.Problem(); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  const double half = 0.5 * options.side;
  const std::array<Eigen::Vector3d, 4> corners = {
      options.centre + Eigen::Vector3d(-half, -half, 0.0),
      options.centre + Eigen::Vector3d(half, -half, 0.0),
      options.centre + Eigen::Vector3d(half, half, 0.0),
      options.centre + Eigen::Vector3d(-half, half, 0.0)};
  std::vector<SquarePoint> points;
  points.reserve(static_cast<size_t>(4 * options.points_per_side));
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector3d& a = corners[static_cast<size_t>(side)];
    const Eigen::Vector3d& b = corners[static_cast<size_t>((side + 1) % 4)];
    for (int k = 0; k < options.points_per_side; ++k) {
      const double s = static_cast<double>(k) / (options.points_per_side - 1);
      // As designed, to the nanometre: square_plan.csv reads -0.01, not -0.009999999999999995.
      const Eigen::Vector3d p =
          (a + s * (b - a)).unaryExpr([](double v) { return DesignedMetres(v); });
      points.push_back({p, side});
    }
  }
  return points;
}

namespace {

// Distance from p to the line through a and b (a != b).
double DistanceToLine(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b) {
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d v = p - a;
  return (v - v.dot(u) * u).norm();
}

}  // namespace

SquareRun SquareErrorsOf(std::vector<Eigen::Vector3d> commanded,
                         std::vector<Eigen::Vector3d> reached, std::vector<int> side) {
  if (commanded.size() != reached.size() || commanded.size() != side.size()) {
    throw std::invalid_argument(fmt::format(
        "square errors: {} commanded points, {} reached, {} side indices (expected as many)",
        commanded.size(), reached.size(), side.size()));
  }
  // Each side's line: through its first and last commanded points (the corners when present).
  std::array<std::vector<size_t>, 4> members;
  for (size_t k = 0; k < side.size(); ++k) {
    if (side[k] < 0 || side[k] > 3) {
      throw std::invalid_argument(
          fmt::format("square errors: point {} is on side {} (expected 1..4)", k + 1, side[k] + 1));
    }
    members[static_cast<size_t>(side[k])].push_back(k);
  }
  for (int s = 0; s < 4; ++s) {
    const auto& m = members[static_cast<size_t>(s)];
    if (m.size() < 2 || (commanded[m.back()] - commanded[m.front()]).norm() < 1e-9) {
      throw std::invalid_argument(fmt::format(
          "side {} of the square has {} point(s){}; at least 2 distinct points are needed to "
          "measure its error",
          s + 1, m.size(), m.size() < 2 ? "" : ", all at one commanded position"));
    }
  }
  SquareRun run;
  run.commanded = std::move(commanded);
  run.reached = std::move(reached);
  run.side = std::move(side);
  // The shape error removes the mean offset: a camera that watches the path sees the
  // square's shape, and a constant offset is the placement of the whole square.
  const double n = static_cast<double>(run.reached.size());
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < run.reached.size(); ++k) offset += run.reached[k] - run.commanded[k];
  run.offset = offset / n;
  run.distance.assign(run.reached.size(), 0.0);
  double total_sq = 0.0, total_shape_sq = 0.0, total_err = 0.0;
  for (int s = 0; s < 4; ++s) {
    const auto& m = members[static_cast<size_t>(s)];
    const Eigen::Vector3d& a = run.commanded[m.front()];
    const Eigen::Vector3d& b = run.commanded[m.back()];
    SquareSideError& e = run.sides[static_cast<size_t>(s)];
    double sum_sq = 0.0, sum_shape_sq = 0.0, sum_err = 0.0;
    for (size_t j : m) {
      const double d = DistanceToLine(run.reached[j], a, b);
      run.distance[j] = d;
      const double d_shape = DistanceToLine(run.reached[j] - run.offset, a, b);
      sum_sq += d * d;
      sum_shape_sq += d_shape * d_shape;
      e.max = std::max(e.max, d);
      e.shape_max = std::max(e.shape_max, d_shape);
      sum_err += (run.reached[j] - run.commanded[j]).norm();
    }
    const double count = static_cast<double>(m.size());
    e.points = static_cast<int>(m.size());
    e.rms = std::sqrt(sum_sq / count);
    e.shape_rms = std::sqrt(sum_shape_sq / count);
    e.mean_position_error = sum_err / count;
    total_sq += sum_sq;
    total_shape_sq += sum_shape_sq;
    total_err += sum_err;
  }
  run.rms = std::sqrt(total_sq / n);
  run.shape_rms = std::sqrt(total_shape_sq / n);
  run.mean_position_error = total_err / n;
  return run;
}

std::vector<RigidTransform> ReachedSquarePoses(const KinematicModel& controller,
                                               const TrueRobotView& truth,
                                               const SquareOptions& options) {
  const std::vector<SquarePoint> points = SquarePoints(options);
  const RigidTransform X_BModel = truth.X_ModelB.inverse();
  std::vector<RigidTransform> reached;
  reached.reserve(points.size());
  std::optional<EePose> guess;
  for (const SquarePoint& point : points) {
    const Eigen::Vector3d& target = point.p_B;
    const EePose x_target(target[0], target[1], target[2], options.theta);
    // The control law: joints from the controller's inverse kinematics.
    const IkResult ik = controller.InverseKinematics(x_target);
    if (!ik.ok()) {
      throw std::invalid_argument(fmt::format(
          "square of side {:.0f} mm: point ({:.1f}, {:.1f}, {:.1f}) mm on side {} is out of "
          "the controller's reach (inverse kinematics has no solution)",
          options.side * 1e3, target[0] * 1e3, target[1] * 1e3, target[2] * 1e3, point.side + 1));
    }
    // Where the true robot goes with those joints.
    const EePose x_true_guess =
        guess ? *guess : EePoseFromTransform(truth.X_ModelB * TransformFromEePose(x_target));
    const FkResult fk = ForwardKinematics(*truth.model, ik.q, x_true_guess);
    if (!fk.ok()) {
      throw std::invalid_argument(fmt::format(
          "square of side {:.0f} mm: the true robot has no pose for the joints commanded at "
          "({:.1f}, {:.1f}, {:.1f}) mm on side {} ({})",
          options.side * 1e3, target[0] * 1e3, target[1] * 1e3, target[2] * 1e3, point.side + 1,
          fk.message));
    }
    guess = fk.x;
    reached.push_back(X_BModel * TransformFromEePose(fk.x));
  }
  return reached;
}

SquareRun RunSquare(const KinematicModel& controller, const TrueRobotView& truth,
                    const SquareOptions& options) {
  const std::vector<SquarePoint> points = SquarePoints(options);
  const std::vector<RigidTransform> X_BE = ReachedSquarePoses(controller, truth, options);
  std::vector<Eigen::Vector3d> commanded, reached;
  std::vector<int> side;
  for (size_t k = 0; k < points.size(); ++k) {
    commanded.push_back(points[k].p_B);
    reached.push_back(X_BE[k].translation());
    side.push_back(points[k].side);
  }
  return SquareErrorsOf(std::move(commanded), std::move(reached), std::move(side));
}

}  // namespace h4::host
