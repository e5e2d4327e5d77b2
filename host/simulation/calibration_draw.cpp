// Simulated intrinsic calibrations; see calibration_draw.h.
#include "host/simulation/calibration_draw.h"

#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>

#include "common/camera/camera_model.h"
#include "common/camera/intrinsics_uncertainty.h"
#include "common/geometry/rotation.h"
#include "common/units.h"

namespace h4::host {

Eigen::MatrixXd ChessboardCalibrationCovariance(const CameraIntrinsics& camera) {
  const CameraModel model(camera);
  std::mt19937_64 rng(25);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<CalibrationViewFit> views;
  for (int v = 0; v < 25; ++v) {
    const double tilt_x = RadiansFromDegrees(35.0 * std::cos(2.4 * v));
    const double tilt_y = RadiansFromDegrees(35.0 * std::sin(2.4 * v));
    const double depth = 0.3 + 0.2 * (v % 5) / 4.0;
    const Eigen::Vector3d centre_C(0.12 * ((v % 5) - 2) / 2.0 * depth / 0.4,
                                   0.09 * ((v / 5) - 2) / 2.0 * depth / 0.4, depth);
    const Eigen::Matrix3d R_CT = RotationFromRpy(Eigen::Vector3d(tilt_x, tilt_y, 0.0));
    const Eigen::Vector3d centre_T(0.1, 0.0625, 0.0);
    CalibrationViewFit view{{}, RigidTransform(R_CT, centre_C - R_CT * centre_T)};
    for (int row = 0; row < 6; ++row) {
      for (int col = 0; col < 9; ++col) {
        const Eigen::Vector3d p_TQ(0.025 * (col - 0.5), 0.025 * (row - 0.5), 0.0);
        Eigen::Vector2d uv;
        if (!model.ProjectVisible(view.X_CT * p_TQ, &uv)) continue;
        if (uv.x() < 0 || uv.y() < 0 || uv.x() > camera.width - 1 || uv.y() > camera.height - 1)
          continue;
        view.corners.p_TQ.push_back(p_TQ);
        view.corners.uv.push_back(uv + Eigen::Vector2d(noise(rng), noise(rng)));
        view.corners.weight.push_back(1.0);
      }
    }
    views.push_back(std::move(view));
  }
  const std::optional<IntrinsicsCovariance> c = IntrinsicsCovarianceOf(camera, views, false);
  if (!c) throw std::runtime_error("the 25 chessboard views do not determine the intrinsics");
  return c->covariance;
}

CameraIntrinsics DrawnFromCovariance(CameraIntrinsics c, const Eigen::MatrixXd& covariance,
                                     uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::VectorXd z(covariance.rows());
  for (Eigen::Index i = 0; i < z.size(); ++i) z[i] = normal(rng);
  const Eigen::VectorXd d = covariance.llt().matrixL() * z;
  c.K(0, 0) += d[0];
  c.K(1, 1) += d[1];
  c.K(0, 2) += d[2];
  c.K(1, 2) += d[3];
  c.distortion += d.tail(c.distortion.size());
  return c;
}

}  // namespace h4::host
