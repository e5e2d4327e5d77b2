// The camera block's names and values; see camera_parameters.h.
#include "host/identification/camera_parameters.h"

#include <algorithm>
#include <stdexcept>

namespace h4::host {
namespace {

std::vector<std::string> DistortionNames(const CameraIntrinsics& camera) {
  static const std::vector<std::string> kRadTan = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};
  static const std::vector<std::string> kEquidistant = {"k1", "k2", "k3", "k4"};
  const std::vector<std::string>& all =
      camera.distortion_model == DistortionModel::kEquidistant ? kEquidistant : kRadTan;
  const size_t n = std::min(all.size(), static_cast<size_t>(camera.distortion.size()));
  return {all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n)};
}

}  // namespace

std::vector<std::string> CameraParameterNames(const CameraIntrinsics& camera) {
  std::vector<std::string> names = {"camera.fx", "camera.fy", "camera.cx", "camera.cy"};
  for (const std::string& d : DistortionNames(camera)) names.push_back("camera." + d);
  return names;
}

Eigen::VectorXd CameraParameterValues(const CameraIntrinsics& camera) {
  const Eigen::Index n = camera.distortion.size();
  Eigen::VectorXd v(4 + n);
  v << camera.K(0, 0), camera.K(1, 1), camera.K(0, 2), camera.K(1, 2), camera.distortion;
  return v;
}

CameraIntrinsics WithCameraParameters(CameraIntrinsics camera, const Eigen::VectorXd& values) {
  if (values.size() != 4 + camera.distortion.size()) {
    throw std::invalid_argument("WithCameraParameters: wrong number of values");
  }
  camera.K(0, 0) = values[0];
  camera.K(1, 1) = values[1];
  camera.K(0, 2) = values[2];
  camera.K(1, 2) = values[3];
  camera.distortion = values.tail(camera.distortion.size());
  return camera;
}

std::vector<std::string> CameraFixPreferences(const CameraIntrinsics& camera) {
  std::vector<std::string> names = CameraParameterNames(camera);
  std::reverse(names.begin(), names.end());
  return names;
}

}  // namespace h4::host
