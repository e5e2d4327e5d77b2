// The accuracy map; see accuracy_map.h for the first-order propagation it implements.
#include "host/validation/accuracy_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/formats/number_text.h"
#include "host/identification/identified_robot.h"
#include "host/identification/parameter_vector.h"
#include "host/kinematics/forward_kinematics.h"

namespace h4::host {
namespace {

// Positions of a range centre - half .. centre + half by step (both ends when they fall on
// the step).
std::vector<double> GridValues(double centre, double half, double step) {
  std::vector<double> values;
  const int n = static_cast<int>(std::floor(2.0 * half / step + 1e-9));
  for (int i = 0; i <= n; ++i) values.push_back(centre - half + i * step);
  return values;
}

// The covariance of the reached pose x' (4x4: X, Y, Z, theta) at commanded pose x, or empty
// when x is out of reach or singular.
std::optional<Eigen::Matrix4d> ReachedPoseCovariance(const KinematicModel& model,
                                                     const Eigen::MatrixXd& C, const EePose& x) {
  const IkResult ik = model.InverseKinematics(x);
  Eigen::MatrixXd J_x_xi;  // -J_f_x^-1 J_f_xi: the sign does not matter to a covariance
  if (!ik.ok() || !ForwardKinematicsJacobians(model, ik.q, x, nullptr, &J_x_xi)) {
    return std::nullopt;
  }
  return J_x_xi * C * J_x_xi.transpose();
}

}  // namespace

bool AccuracyMapOptions::IsValid(std::string* why) const {
  const auto fail = [why](const char* what) {
    if (why != nullptr) *why = what;
    return false;
  };
  if (!(half_extent_m >= 0.0 && half_extent_m <= 1.0)) return fail("half extent must be 0-1 m");
  if (!(step_m > 0.0) || half_extent_m / step_m > 200.0) {
    return fail("step must be positive and at most 200 steps per half extent");
  }
  if (z_offsets_m.empty() || theta_rad.empty()) return fail("needs a Z level and a theta");
  return true;
}

double AccuracyMap::MedianPositionSigma() const {
  if (points.empty()) return 0.0;
  std::vector<double> sigmas;
  for (const AccuracyMapPoint& point : points) sigmas.push_back(point.position_sigma_m);
  const auto middle = sigmas.begin() + static_cast<long>(sigmas.size() / 2);
  std::nth_element(sigmas.begin(), middle, sigmas.end());
  return *middle;
}

double AccuracyMap::MaxPositionSigma() const {
  double largest = 0.0;
  for (const AccuracyMapPoint& point : points) {
    largest = std::max(largest, point.position_sigma_m);
  }
  return largest;
}

AccuracyMap ComputeAccuracyMap(const KinematicModel& model, const Eigen::MatrixXd& C,
                               const AccuracyMapOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("accuracy map: " + why);
  const Eigen::Index n = model.parameters().size();
  if (C.rows() != n || C.cols() != n) {
    throw std::invalid_argument("accuracy map: the covariance must be one row and column per "
                                "kinematic parameter");
  }
  AccuracyMap map;
  map.model = model.kind();
  map.centre = model.WorkspaceCentre();
  map.options = options;
  const std::vector<double> xs = GridValues(map.centre[0], options.half_extent_m, options.step_m);
  const std::vector<double> ys = GridValues(map.centre[1], options.half_extent_m, options.step_m);
  for (double dz : options.z_offsets_m) {
    for (double theta : options.theta_rad) {
      for (double y : ys) {
        for (double x : xs) {
          const EePose pose(x, y, map.centre[2] + dz, theta);
          const std::optional<Eigen::Matrix4d> S = ReachedPoseCovariance(model, C, pose);
          if (!S) {
            ++map.left_out;
            continue;
          }
          map.points.push_back({pose, std::sqrt(std::max(0.0, S->topLeftCorner<3, 3>().trace())),
                                std::sqrt(std::max(0.0, (*S)(3, 3)))});
        }
      }
    }
  }
  return map;
}

std::optional<AccuracyMap> AccuracyMapOfResult(const IdentificationResult& result,
                                               const Assembly& assembly,
                                               const AccuracyMapOptions& options) {
  if (!result.parameter_covariance) return std::nullopt;
  const IdentifiedRobot robot = RebuildFromResult(result, assembly);
  const ParameterVector p(*robot.model, robot.X_BC, robot.X_TE);
  const Eigen::MatrixXd C = ResultCovarianceFor(result, p);
  const Eigen::Index n = p.kinematic_count();
  return ComputeAccuracyMap(*robot.model, C.topLeftCorner(n, n), options);
}

std::string AccuracyMapCsv(const AccuracyMap& map) {
  std::string csv = "X,Y,Z,theta,position_sigma,theta_sigma\n";
  for (const AccuracyMapPoint& point : map.points) {
    csv += FormatDouble(point.x[0], "X") + "," + FormatDouble(point.x[1], "Y") + "," +
           FormatDouble(point.x[2], "Z") + "," + FormatDouble(point.x[3], "theta") + "," +
           FormatDouble(point.position_sigma_m, "position_sigma") + "," +
           FormatDouble(point.theta_sigma_rad, "theta_sigma") + "\n";
  }
  return csv;
}

}  // namespace h4::host
