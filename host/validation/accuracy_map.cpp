// The accuracy map; see accuracy_map.h for the first-order propagation it implements.
#include "host/validation/accuracy_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "common/formats/number_text.h"
#include "common/text/invalid_reason.h"
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

// The sensitivity of the reached pose x' (X, Y, Z, theta) to the kinematic parameters at
// commanded pose x, J_f_x^-1 J_f_xi up to its sign (which a covariance does not see), or
// empty when x is out of reach or singular.
std::optional<Eigen::MatrixXd> ReachedPoseSensitivity(const KinematicModel& model,
                                                      const EePose& x) {
  const IkResult ik = model.InverseKinematics(x);
  Eigen::MatrixXd J_x_xi;
  if (!ik.ok() || !ForwardKinematicsJacobians(model, ik.q, x, nullptr, &J_x_xi)) {
    return std::nullopt;
  }
  return J_x_xi;
}

// The grid's poses in Z level, theta, Y, X order.
std::vector<EePose> GridPoses(const EePose& centre, const AccuracyMapOptions& options) {
  const std::vector<double> xs = GridValues(centre[0], options.half_extent_m, options.step_m);
  const std::vector<double> ys = GridValues(centre[1], options.half_extent_m, options.step_m);
  std::vector<EePose> poses;
  for (double dz : options.z_offsets_m) {
    for (double theta : options.theta_rad) {
      for (double y : ys) {
        for (double x : xs) poses.emplace_back(x, y, centre[2] + dz, theta);
      }
    }
  }
  return poses;
}

// H (4x4) of pose x: how its (X, Y, Z, theta) move under a small rigid motion of the base
// frame (translation t, rotation a about Z through `centre`): d = H (t, a).
Eigen::Matrix4d RigidMotionRows(const EePose& x, const EePose& centre) {
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H(0, 3) = -(x[1] - centre[1]);
  H(1, 3) = x[0] - centre[0];
  return H;
}

}  // namespace

bool AccuracyMapOptions::IsValid(std::string* why) const {
  if (!(half_extent_m >= 0.0 && half_extent_m <= 1.0))
    return Invalid(why, "half extent must be 0-1 m");
  if (!(step_m > 0.0) || half_extent_m / step_m > 200.0) {
    return Invalid(why, "step must be positive and at most 200 steps per half extent");
  }
  if (z_offsets_m.empty() || theta_rad.empty()) return Invalid(why, "needs a Z level and a theta");
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
  std::vector<EePose> reached;
  std::vector<Eigen::MatrixXd> sensitivity;
  for (const EePose& pose : GridPoses(map.centre, options)) {
    std::optional<Eigen::MatrixXd> A = ReachedPoseSensitivity(model, pose);
    if (!A) {
      ++map.left_out;
      continue;
    }
    reached.push_back(pose);
    sensitivity.push_back(std::move(*A));
  }
  if (options.register_base_frame) {
    sensitivity = WithoutRigidRegistration(reached, map.centre, sensitivity);
  }
  for (size_t k = 0; k < reached.size(); ++k) {
    const Eigen::Matrix4d S = sensitivity[k] * C * sensitivity[k].transpose();
    const double position_sigma = std::sqrt(std::max(0.0, S.topLeftCorner<3, 3>().trace()));
    const double theta_sigma = std::sqrt(std::max(0.0, S(3, 3)));
    // A covariance too large for doubles gives no sigma (inf, or NaN that std::max(0, NaN)
    // would turn into 0, hence the check of S itself): the pose is left out rather than
    // printed or plotted as inf, which neither the median nor gnuplot can take.
    if (!std::isfinite(position_sigma) || !std::isfinite(theta_sigma) || !S.allFinite()) {
      ++map.left_out;
      continue;
    }
    map.points.push_back({reached[k], position_sigma, theta_sigma});
  }
  return map;
}

std::vector<Eigen::MatrixXd> WithoutRigidRegistration(const std::vector<EePose>& poses,
                                                      const EePose& centre,
                                                      const std::vector<Eigen::MatrixXd>& errors) {
  if (poses.empty()) return errors;
  // The rigid motion (t, a) that best explains the position rows over every pose, least
  // squares: (sum H3^T H3) g = sum H3^T e3, H3 the position rows of RigidMotionRows.
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(4, errors.front().cols());
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Matrix<double, 3, 4> H3 = RigidMotionRows(poses[k], centre).topRows<3>();
    normal += H3.transpose() * H3;
    rhs += H3.transpose() * errors[k].topRows(3);
  }
  const Eigen::MatrixXd g = normal.ldlt().solve(rhs);
  std::vector<Eigen::MatrixXd> left;
  for (size_t k = 0; k < poses.size(); ++k) {
    left.push_back(errors[k] - RigidMotionRows(poses[k], centre) * g);
  }
  return left;
}

std::vector<Eigen::Vector4d> ResidualAfterRigidRegistration(const std::vector<EePose>& commanded,
                                                            const std::vector<EePose>& reached) {
  std::vector<Eigen::Vector4d> residuals;
  if (commanded.empty() || commanded.size() != reached.size()) return residuals;
  Eigen::Vector3d mean_commanded = Eigen::Vector3d::Zero(), mean_reached = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < commanded.size(); ++k) {
    mean_commanded += commanded[k].head<3>();
    mean_reached += reached[k].head<3>();
  }
  mean_commanded /= static_cast<double>(commanded.size());
  mean_reached /= static_cast<double>(reached.size());
  // The rotation about Z that best turns the centred commanded X-Y positions onto the
  // reached ones: atan2 of the summed cross and dot products (2-D Procrustes).
  double cross = 0.0, dot = 0.0;
  for (size_t k = 0; k < commanded.size(); ++k) {
    const Eigen::Vector3d u = commanded[k].head<3>() - mean_commanded;
    const Eigen::Vector3d v = reached[k].head<3>() - mean_reached;
    cross += u.x() * v.y() - u.y() * v.x();
    dot += u.x() * v.x() + u.y() * v.y();
  }
  const double angle = std::atan2(cross, dot);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (size_t k = 0; k < commanded.size(); ++k) {
    const Eigen::Vector3d moved = R * (commanded[k].head<3>() - mean_commanded) + mean_reached;
    Eigen::Vector4d r;
    r.head<3>() = reached[k].head<3>() - moved;
    r[3] = std::remainder(reached[k][3] - commanded[k][3] - angle, 2.0 * std::numbers::pi);
    residuals.push_back(r);
  }
  return residuals;
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
