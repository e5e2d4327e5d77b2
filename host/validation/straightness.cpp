// Straightness (Table 4) and simulated ruler runs (see straightness.h).
#include "host/validation/straightness.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <spdlog/fmt/fmt.h>

#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"

namespace h4::host {

bool FitLine(const std::vector<Eigen::Vector3d>& points, LineFit* fit) {
  if (points.size() < 3) return false;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  // Largest eigenvalue last: the direction of most spread.
  const Eigen::Vector3d direction = eigen.eigenvectors().col(2).normalized();
  double lo = 0.0, hi = 0.0, sum_sq = 0.0, max_d = 0.0;
  std::vector<double> distances;
  for (const auto& p : points) {
    const Eigen::Vector3d v = p - centroid;
    const double along = v.dot(direction);
    lo = std::min(lo, along);
    hi = std::max(hi, along);
    const double d = (v - along * direction).norm();
    distances.push_back(d);
    sum_sq += d * d;
    max_d = std::max(max_d, d);
  }
  if (hi - lo < 1e-3) return false;
  fit->point = centroid;
  fit->direction = direction;
  fit->distances = std::move(distances);
  fit->rms_distance = std::sqrt(sum_sq / static_cast<double>(points.size()));
  fit->max_distance = max_d;
  fit->length = hi - lo;
  return true;
}

StraightnessRun StraightnessOf(const KinematicModel& model, const std::vector<JointsRow>& joints) {
  StraightnessRun run;
  std::optional<EePose> guess;
  for (const JointsRow& row : joints) {
    const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
    const FkResult fk = ForwardKinematics(model, q, guess);
    if (!fk.ok()) {
      run.failed.push_back(row.pose_id);
      continue;
    }
    guess = fk.x;
    run.pose_ids.push_back(row.pose_id);
    run.positions.push_back(fk.x.head<3>());
  }
  if (run.positions.size() < 3) {
    run.message = fmt::format("forward kinematics gave a pose for {} of {} readings (need 3)",
                              run.positions.size(), joints.size());
    return run;
  }
  if (!FitLine(run.positions, &run.fit)) {
    run.message = "the positions do not spread over 1 mm: no line to fit";
    return run;
  }
  run.ok = true;
  return run;
}

std::vector<JointsRow> SimulateRulerRun(const SimulatedRobot& robot, const RulerLine& line,
                                        double sigma_q, uint64_t seed) {
  if (line.count < 3) throw std::invalid_argument("a ruler run needs at least 3 poses");
  const std::unique_ptr<KinematicModel> model = robot.MakeModel();
  const RigidTransform X_ModelB = robot.X_ModelB();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<JointsRow> rows;
  for (int k = 0; k < line.count; ++k) {
    const double s = static_cast<double>(k) / (line.count - 1);
    const EePose x_B = line.start + s * (line.end - line.start);
    const EePose x_model = EePoseFromTransform(X_ModelB * TransformFromEePose(x_B));
    const IkResult ik = model->InverseKinematics(x_model);
    if (!ik.ok()) {
      throw std::invalid_argument(
          fmt::format("ruler pose {} ({:.3f}, {:.3f}, {:.3f}) m is out of the true robot's reach",
                      k + 1, x_B[0], x_B[1], x_B[2]));
    }
    JointsRow row;
    row.pose_id = k + 1;
    for (int i = 0; i < 4; ++i) row.q[i] = ik.q[i] + sigma_q * noise(rng);
    rows.push_back(row);
  }
  return rows;
}

std::vector<RulerLine> PaperRulerLines() {
  const double half = 0.08;
  const double diag = half / std::sqrt(2.0);
  RulerLine x_line;
  x_line.start = EePose(-half, 0.0, -0.45, 0.0);
  x_line.end = EePose(half, 0.0, -0.45, 0.0);
  RulerLine diagonal;
  diagonal.start = EePose(-diag, -diag, -0.45, 0.0);
  diagonal.end = EePose(diag, diag, -0.45, 0.0);
  return {x_line, diagonal};
}

}  // namespace h4::host
