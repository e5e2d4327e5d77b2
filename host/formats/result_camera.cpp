// See result_camera.h.
#include "host/formats/result_camera.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "common/formats/number_text.h"
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

}  // namespace

ResultCamera ReadResultCamera(const JsonValue& object) {
  object.RequireObject();
  ResultCamera camera;
  camera.distortion_model = object["distortion_model"].String();
  if (camera.distortion_model != "radtan" && camera.distortion_model != "equidistant") {
    object["distortion_model"].Fail("expected \"radtan\" or \"equidistant\"");
  }
  camera.width = static_cast<int>(object["width"].Integer());
  camera.height = static_cast<int>(object["height"].Integer());
  if (camera.width <= 0 || camera.height <= 0 || camera.width > 100000 || camera.height > 100000) {
    object["width"].Fail("expected an image size of 1 to 100000 px");
  }
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
    if (!C.isApprox(C.transpose(), 1e-9) && C.norm() > 0) field.Fail("expected a symmetric matrix");
    camera.covariance = C;
  }
  camera.corners = static_cast<int>(object["corners"].Integer());
  camera.rejected_corners = static_cast<int>(object["rejected_corners"].Integer());
  camera.corner_rms_px = object["corner_rms_px"].NonNegativeNumber();
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
