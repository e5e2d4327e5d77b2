// The square measured by the camera: plan rows, their reading back, and the side errors of
// the measured path (see measured_square.h).
#include "host/validation/measured_square.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include <spdlog/fmt/fmt.h>

namespace h4::host {

std::vector<EndEffectorPoseRow> SquarePlanPoses(const SquareOptions& options, int64_t first_id) {
  std::vector<EndEffectorPoseRow> rows;
  int64_t id = first_id;
  for (const SquarePoint& point : SquarePoints(options)) {
    rows.push_back({id++, point.p_B[0], point.p_B[1], point.p_B[2], options.theta});
  }
  return rows;
}

SquarePlan SquarePlanFromPoses(const std::vector<EndEffectorPoseRow>& rows,
                               const std::string& source_name) {
  const size_t n = rows.size();
  if (n < 8 || n % 4 != 0) {
    throw std::invalid_argument(fmt::format(
        "{}: {} points; a square plan has 4 sides of the same number (at least 2) of points, "
        "in path order (write it with h4cal square-plan)",
        source_name, n));
  }
  const int per_side = static_cast<int>(n / 4);
  auto position = [](const EndEffectorPoseRow& r) { return Eigen::Vector3d(r.X, r.Y, r.Z); };
  // The square the rows describe: the mean of the sides' points is the centre (each side is
  // symmetric about its midpoint), side 1 runs from the first row to the per_side-th.
  SquareOptions options;
  options.points_per_side = per_side;
  options.theta = rows.front().theta;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& r : rows) centre += position(r);
  options.centre = centre / static_cast<double>(n);
  options.side =
      (position(rows[static_cast<size_t>(per_side - 1)]) - position(rows.front())).norm();
  if (const std::string problem = options.Problem(); !problem.empty()) {
    throw std::invalid_argument(fmt::format("{}: not a square plan: {}", source_name, problem));
  }
  const std::vector<SquarePoint> expected = SquarePoints(options);
  constexpr double kTolerance = 1e-6;  // m: a plan is written with full precision
  SquarePlan plan;
  plan.options = options;
  for (size_t k = 0; k < n; ++k) {
    const EndEffectorPoseRow& r = rows[k];
    const Eigen::Vector3d p = position(r);
    const SquarePoint& e = expected[k];
    if ((p - e.p_B).norm() > kTolerance || std::abs(r.theta - options.theta) > 1e-9) {
      throw std::invalid_argument(fmt::format(
          "{}: row {} (pose_id {}) at ({:.4f}, {:.4f}, {:.4f}) mm, theta {:.6f} rad is not "
          "point {} of side {} of the {:.3f} mm square centred at ({:.3f}, {:.3f}, {:.3f}) mm "
          "with theta {:.6f} rad: expected ({:.4f}, {:.4f}, {:.4f}) mm; a plan lists the "
          "square's points in path order, as h4cal square-plan writes them",
          source_name, k + 1, r.pose_id, p[0] * 1e3, p[1] * 1e3, p[2] * 1e3, r.theta,
          k % static_cast<size_t>(per_side) + 1, e.side + 1, options.side * 1e3,
          options.centre[0] * 1e3, options.centre[1] * 1e3, options.centre[2] * 1e3, options.theta,
          e.p_B[0] * 1e3, e.p_B[1] * 1e3, e.p_B[2] * 1e3));
    }
    plan.pose_ids.push_back(r.pose_id);
    plan.commanded.push_back(p);
    plan.side.push_back(e.side);
  }
  return plan;
}

MeasuredSquareRun MeasuredSquareOf(const SquarePlan& plan, const std::vector<DatasetRow>& rows,
                                   const RigidTransform& X_BC, const RigidTransform& X_TE,
                                   const std::string& label, const std::string& dataset_name) {
  std::unordered_map<int64_t, const DatasetRow*> by_id;
  for (const DatasetRow& row : rows) by_id[row.pose_id] = &row;
  MeasuredSquareRun out;
  out.label = label;
  out.dataset_name = dataset_name;
  out.planned = plan.pose_ids.size();
  std::vector<Eigen::Vector3d> commanded, measured;
  std::vector<int> side;
  std::array<std::vector<int64_t>, 4> missing_on_side;
  for (size_t k = 0; k < plan.pose_ids.size(); ++k) {
    const auto it = by_id.find(plan.pose_ids[k]);
    if (it == by_id.end()) {
      out.missing_ids.push_back(plan.pose_ids[k]);
      missing_on_side[static_cast<size_t>(plan.side[k])].push_back(plan.pose_ids[k]);
      continue;
    }
    // Eq. (6): the end-effector pose the camera saw.
    const RigidTransform X_BE = X_BC * it->second->X_CT * X_TE;
    commanded.push_back(plan.commanded[k]);
    measured.push_back(X_BE.translation());
    side.push_back(plan.side[k]);
  }
  std::unordered_set<int64_t> planned(plan.pose_ids.begin(), plan.pose_ids.end());
  for (const DatasetRow& row : rows) out.unplanned_rows += planned.count(row.pose_id) ? 0 : 1;
  for (int s = 0; s < 4; ++s) {
    const auto& missing = missing_on_side[static_cast<size_t>(s)];
    const int points = plan.options.points_per_side - static_cast<int>(missing.size());
    if (points < 2) {
      throw std::invalid_argument(fmt::format(
          "{} ({} controller): side {} of the square has {} measured point(s) of {} (missing "
          "pose ids {}); at least 2 are needed. Is this the dataset collected with the plan?",
          dataset_name, label, s + 1, points, plan.options.points_per_side, PoseIdList(missing)));
    }
  }
  out.run = SquareErrorsOf(std::move(commanded), std::move(measured), std::move(side));
  return out;
}

std::string PoseIdList(const std::vector<int64_t>& ids, size_t limit) {
  const auto listed = ids.begin() + static_cast<std::ptrdiff_t>(std::min(limit, ids.size()));
  std::string text = fmt::format("{}", fmt::join(ids.begin(), listed, ", "));
  if (ids.size() > limit) fmt::format_to(std::back_inserter(text), ", ... ({} in all)", ids.size());
  return text;
}

}  // namespace h4::host
