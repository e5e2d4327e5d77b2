// Camera intrinsics in OpenCV FileStorage YAML; see camera_yaml.h.
#include "common/formats/camera_yaml.h"

#include <limits>

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "common/formats/yaml_map.h"

namespace h4 {
namespace {

// OpenCV's "%YAML:1.0" is not a valid YAML 1.2 directive. Blank that line (rather than
// removing it) so that yaml-cpp's line numbers stay those of the file.
std::string WithoutOpenCvDirective(const std::string& text) {
  if (text.rfind("%YAML:", 0) != 0) return text;
  const size_t newline = text.find('\n');
  return newline == std::string::npos ? std::string() : text.substr(newline);
}

struct Matrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> data;  // row-major
};

Matrix ReadMatrix(const YamlMap& root, const std::string& key) {
  const YamlMap m = root.Map(key);
  m.RejectUnknownKeys({"rows", "cols", "dt", "data"});
  Matrix matrix;
  const int64_t rows = m.Int("rows");
  const int64_t cols = m.Int("cols");
  if (rows < 1 || rows > 64) m.Fail("rows", "expected a row count in 1..64");
  if (cols < 1 || cols > 64) m.Fail("cols", "expected a column count in 1..64");
  matrix.rows = static_cast<int>(rows);
  matrix.cols = static_cast<int>(cols);
  const std::string dt = m.String("dt");
  if (dt != "d" && dt != "f") m.Fail("dt", "expected 'd' or 'f' (real numbers), got '" + dt + "'");
  matrix.data = m.Doubles("data", static_cast<size_t>(rows * cols));
  return matrix;
}

void RequireValue(const YamlMap& root, const Matrix& K, size_t index, double expected) {
  if (K.data[index] != expected) {
    const YamlMap m = root.Map("camera_matrix");
    m.FailElement("data", index,
                  "expected " + FormatDouble(expected, "K") + " in a camera matrix, got " +
                      FormatDouble(K.data[index], "K"));
  }
}

// A number OpenCV's parser reads as a real: it takes "500" for an integer.
std::string Real(double value, const std::string& field) {
  std::string text = FormatDouble(value, field);
  if (text.find_first_of(".e") == std::string::npos) text += ".";
  return text;
}

std::string WriteMatrix(const std::string& name, int rows, int cols, const double* row_major) {
  std::string text = name + ": !!opencv-matrix\n   rows: " + std::to_string(rows) +
                     "\n   cols: " + std::to_string(cols) + "\n   dt: d\n   data: [ ";
  for (int i = 0; i < rows * cols; ++i) {
    text += (i ? ", " : "") + Real(row_major[i], name);
  }
  return text + " ]\n";
}

}  // namespace

CameraIntrinsics ParseCameraYaml(const std::string& text, const std::string& source_name) {
  const YamlMap root(LoadYaml(WithoutOpenCvDirective(text), source_name), source_name, "", 0);
  root.RejectCaseVariants({"image_width", "image_height", "camera_matrix",
                           "distortion_coefficients", "avg_reprojection_error"});
  CameraIntrinsics camera;
  const auto image_size = [&root](const std::string& key) {
    const int64_t size = root.Int(key);
    if (size < 1 || size > std::numeric_limits<int>::max()) {
      root.Fail(key, "expected a positive image size in px, got " + std::to_string(size));
    }
    return static_cast<int>(size);
  };
  camera.width = image_size("image_width");
  camera.height = image_size("image_height");
  const Matrix K = ReadMatrix(root, "camera_matrix");
  if (K.rows != 3 || K.cols != 3) {
    root.Map("camera_matrix")
        .Fail("rows", "expected a 3x3 camera matrix, got " + std::to_string(K.rows) + "x" +
                          std::to_string(K.cols));
  }
  for (size_t index : {0u, 4u}) {
    if (!(K.data[index] > 0.0)) {
      root.Map("camera_matrix")
          .FailElement("data", index, "expected a positive focal length in px (fx, fy)");
    }
  }
  RequireValue(root, K, 3, 0.0);
  RequireValue(root, K, 6, 0.0);
  RequireValue(root, K, 7, 0.0);
  RequireValue(root, K, 8, 1.0);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) camera.K(r, c) = K.data[static_cast<size_t>(3 * r + c)];
  }
  const Matrix D = ReadMatrix(root, "distortion_coefficients");
  const size_t n = D.data.size();
  if ((D.rows != 1 && D.cols != 1) || (n != 4 && n != 5 && n != 8)) {
    root.Map("distortion_coefficients")
        .Fail("rows",
              "expected a 1xN or Nx1 matrix with N = 4, 5 or 8 (k1 k2 p1 p2 [k3 [k4 "
              "k5 k6]]), got " +
                  std::to_string(D.rows) + "x" + std::to_string(D.cols));
  }
  camera.distortion =
      Eigen::Map<const Eigen::VectorXd>(D.data.data(), static_cast<Eigen::Index>(n));
  if (root.Has("avg_reprojection_error")) {
    const double error = root.Double("avg_reprojection_error");
    if (error < 0.0) root.Fail("avg_reprojection_error", "expected a non-negative RMS in px");
    camera.avg_reprojection_error = error;
  }
  return camera;
}

CameraIntrinsics ReadCameraYaml(const std::string& path) {
  return ParseCameraYaml(ReadTextFile(path), path);
}

std::string FormatCameraYaml(const CameraIntrinsics& camera) {
  std::string text = "%YAML:1.0\n---\nimage_width: " + std::to_string(camera.width) +
                     "\nimage_height: " + std::to_string(camera.height) + "\n";
  double K[9];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) K[3 * r + c] = camera.K(r, c);
  }
  text += WriteMatrix("camera_matrix", 3, 3, K);
  const Eigen::VectorXd& d = camera.distortion;
  text += WriteMatrix("distortion_coefficients", static_cast<int>(d.size()), 1, d.data());
  if (camera.avg_reprojection_error) {
    text += "avg_reprojection_error: " +
            Real(*camera.avg_reprojection_error, "avg_reprojection_error") + "\n";
  }
  return text;
}

void WriteCameraYaml(const std::string& path, const CameraIntrinsics& camera) {
  WriteTextFile(path, FormatCameraYaml(camera));
}

}  // namespace h4
