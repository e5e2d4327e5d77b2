// See result_camera.h.
#include "host/formats/result_camera.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/camera/camera_intrinsics.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/number_text.h"
#include "common/geometry/covariance_check.h"
#include "host/formats/json_fields.h"

namespace h4 {
namespace {

using Ordered = nlohmann::ordered_json;

Ordered FiniteNumber(double value, const std::string& field) {
  FormatDouble(value, field);  // throws on a non-finite value
  return value;
}

ResultCameraParameter ReadParameter(const JsonValue& entry) {
  ResultCameraParameter p;
  p.name = entry["name"].String();
  if (p.name.rfind("camera.", 0) != 0) entry["name"].Fail("expected a name camera.<parameter>");
  p.value = entry["value"].Number();
  p.file_value = entry["file_value"].Number();
  p.std = entry["std"].NumberOrNull();
  if (p.std && !(*p.std >= 0.0 && *p.std < 1e6)) entry["std"].Fail("expected a sigma in [0, 1e6)");
  if (entry.HasNonNull("fixed_reason")) p.fixed_reason = entry["fixed_reason"].String();
  const bool focal = p.name == "camera.fx" || p.name == "camera.fy";
  if (focal && !(p.value > 0.0)) entry["value"].Fail("expected a positive focal length");
  return p;
}

// The intrinsics the parameters hold (their values, or the file's): fx, fy, cx, cy in this
// order, then the distortion coefficients; empty when the names are not in that order.
std::optional<CameraIntrinsics> IntrinsicsOf(const ResultCamera& camera, bool file_values) {
  static const char* kFirst[4] = {"camera.fx", "camera.fy", "camera.cx", "camera.cy"};
  const size_t n = camera.parameters.size();
  if (n < 4) return std::nullopt;
  for (size_t i = 0; i < 4; ++i) {
    if (camera.parameters[i].name != kFirst[i]) return std::nullopt;
  }
  const auto value = [&](size_t i) {
    return file_values ? camera.parameters[i].file_value : camera.parameters[i].value;
  };
  CameraIntrinsics intrinsics = CameraIntrinsics::Pinhole(camera.width, camera.height, value(0),
                                                          value(1), value(2), value(3));
  intrinsics.K(0, 1) = camera.skew;
  intrinsics.distortion_model = *DistortionModelFromName(camera.distortion_model);
  intrinsics.distortion.resize(static_cast<Eigen::Index>(n - 4));
  for (size_t i = 4; i < n; ++i) intrinsics.distortion[static_cast<Eigen::Index>(i - 4)] = value(i);
  return intrinsics;
}

// The camera block bounded as the camera file's reader bounds a camera (camera_yaml.h): a
// principal point of 1e300 px was read and ended in gnuplot's "undefined variable: inf".
void RequirePhysicalCamera(const JsonValue& object, const ResultCamera& camera) {
  for (const bool file_values : {false, true}) {
    const std::optional<CameraIntrinsics> intrinsics = IntrinsicsOf(camera, file_values);
    if (!intrinsics) {
      object["parameters"].Fail(
          "expected camera.fx, camera.fy, camera.cx, camera.cy, then the distortion "
          "coefficients");
    }
    if (const std::string problem = CameraIntrinsicsProblem(*intrinsics); !problem.empty()) {
      object["parameters"].Fail(std::string(file_values ? "the file's camera (file_value): "
                                                        : "the refined camera (value): ") +
                                problem);
    }
  }
}

// The covariance a covariance (common/geometry/covariance_check.h) whose diagonal is the
// parameters' std squared, with zero rows for the parameters kept from the file.
void RequireCovarianceOfTheSigmas(const JsonValue& field, const ResultCamera& camera) {
  const Eigen::MatrixXd& C = *camera.covariance;
  if (const std::string problem = CovarianceProblem(C); !problem.empty()) {
    field.Fail("expected a covariance: it is " + problem);
  }
  for (size_t i = 0; i < camera.parameters.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const std::optional<double>& sigma = camera.parameters[i].std;
    const double expected = sigma ? *sigma * *sigma : 0.0;
    const bool row_zero = sigma || C.row(k).isZero(0.0);
    if (!(std::abs(C(k, k) - expected) <= 1e-9 * expected) || !row_zero) {
      field.Fail(fmt::format(
          "expected {:g} on the diagonal at {} (the std of {} squared{}), got {:g}", expected, i,
          camera.parameters[i].name, sigma ? "" : ": kept from the file, so a zero row", C(k, k)));
    }
  }
}

}  // namespace

ResultCamera ReadResultCamera(const JsonValue& object) {
  object.RequireObject();
  ResultCamera camera;
  camera.distortion_model = object["distortion_model"].String();
  if (camera.distortion_model != "radtan" && camera.distortion_model != "equidistant") {
    object["distortion_model"].Fail("expected \"radtan\" or \"equidistant\"");
  }
  const int64_t width = object["width"].Integer();
  const int64_t height = object["height"].Integer();
  if (const std::string problem = ImageSizeProblem(width, height); !problem.empty()) {
    object["width"].Fail("expected the camera file's image size: " + problem);
  }
  camera.width = static_cast<int>(width);
  camera.height = static_cast<int>(height);
  camera.skew = object["skew"].Number();
  const JsonValue list = object["parameters"];
  const size_t n = list.ArraySize();
  for (size_t i = 0; i < n; ++i) camera.parameters.push_back(ReadParameter(list.At(i)));
  if (object.HasNonNull("covariance")) {
    const JsonValue field = object["covariance"];
    field.ArraySize(n);
    Eigen::MatrixXd C(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (size_t i = 0; i < n; ++i) {
      const std::vector<double> row = field.At(i).Numbers(n);
      for (size_t j = 0; j < n; ++j)
        C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = row[j];
    }
    camera.covariance = C;
    RequireCovarianceOfTheSigmas(field, camera);
  }
  camera.corners = static_cast<int>(object["corners"].Integer());
  camera.rejected_corners = static_cast<int>(object["rejected_corners"].Integer());
  camera.corner_rms_px = object["corner_rms_px"].NonNegativeNumber();
  RequirePhysicalCamera(object, camera);
  return camera;
}

Ordered ResultCameraJson(const ResultCamera& camera) {
  Ordered parameters = Ordered::array();
  for (const ResultCameraParameter& p : camera.parameters) {
    parameters.push_back(
        {{"name", p.name},
         {"value", FiniteNumber(p.value, "camera." + p.name)},
         {"file_value", FiniteNumber(p.file_value, "camera." + p.name + ".file_value")},
         {"std", p.std ? FiniteNumber(*p.std, "camera." + p.name + ".std") : Ordered(nullptr)},
         {"fixed_reason", p.fixed_reason.empty() ? Ordered(nullptr) : Ordered(p.fixed_reason)}});
  }
  Ordered covariance = nullptr;
  if (camera.covariance) {
    covariance = Ordered::array();
    for (Eigen::Index i = 0; i < camera.covariance->rows(); ++i) {
      Ordered row = Ordered::array();
      for (Eigen::Index j = 0; j < camera.covariance->cols(); ++j) {
        row.push_back(FiniteNumber((*camera.covariance)(i, j), "camera.covariance"));
      }
      covariance.push_back(row);
    }
  }
  return {{"distortion_model", camera.distortion_model},
          {"width", camera.width},
          {"height", camera.height},
          {"skew", FiniteNumber(camera.skew, "camera.skew")},
          {"parameters", parameters},
          {"covariance", covariance},
          {"corners", camera.corners},
          {"rejected_corners", camera.rejected_corners},
          {"corner_rms_px", FiniteNumber(camera.corner_rms_px, "camera.corner_rms_px")}};
}

}  // namespace h4
