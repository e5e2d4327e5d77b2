// The `camera` key of the identification result JSON
// (common/formats/README.md#identification-result-json-h4cal-identify---out): the intrinsics the
// corner path refined together with the robot, their file values, sigmas and covariance. Absent
// (null) on the pose path.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

namespace h4 {

struct ResultCameraParameter {
  std::string name;           ///< camera.fx, camera.fy, camera.cx, camera.cy, camera.k1, ...
  double value = 0.0;         ///< refined (or kept) value, px or plain coefficient
  double file_value = 0.0;    ///< the camera file's value
  std::optional<double> std;  ///< one sigma; empty when kept from the file
  std::string fixed_reason;   ///< why it was kept from the file; empty when refined
};

struct ResultCamera {
  std::string distortion_model;  ///< "radtan" | "equidistant"
  int width = 0;                 ///< px
  int height = 0;
  double skew = 0.0;  ///< px, held at the file's value
  std::vector<ResultCameraParameter> parameters;
  /// Over `parameters` in their order (zero rows for kept ones); absent when not computed.
  std::optional<Eigen::MatrixXd> covariance;
  int corners = 0;             ///< in the fit
  int rejected_corners = 0;    ///< corner outliers
  double corner_rms_px = 0.0;  ///< per-axis RMS of the corner residuals after the fit
};

class JsonValue;
/// Reads the object; throws FormatError naming the field: finite numbers, std >= 0, the
/// refined and the file's camera each within the camera file's bounds
/// (CameraIntrinsicsProblem, common/formats/camera_yaml.h: image size, focal lengths,
/// principal point in the image, coefficient count, no fold inside the image), the
/// covariance n x n, symmetric and positive semi-definite with the std's squares on its
/// diagonal (zero rows for parameters kept from the file).
ResultCamera ReadResultCamera(const JsonValue& object);
/// The object as written; throws std::invalid_argument on a non-finite number.
nlohmann::ordered_json ResultCameraJson(const ResultCamera& camera);

}  // namespace h4
