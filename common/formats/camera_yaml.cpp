// Camera intrinsics in OpenCV FileStorage YAML or a Kalibr camchain; see camera_yaml.h.
#include "common/formats/camera_yaml.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Eigenvalues>
#include <fmt/core.h>

#include "common/camera/camera_model.h"
#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
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
  std::string text = fmt::format(
      "{}: !!opencv-matrix\n"
      "   rows: {}\n"
      "   cols: {}\n"
      "   dt: d\n"
      "   data: [ ",
      name, rows, cols);
  for (int i = 0; i < rows * cols; ++i) {
    text += (i ? ", " : "") + Real(row_major[i], name);
  }
  return text + " ]\n";
}

std::string SizeLimits() { return ImageSizeLimits(); }

int ImageSize(const YamlMap& root, const std::string& key) {
  const int64_t size = root.Int(key);
  if (size < kMinImageSide_px || size > kMaxImageSide_px) {
    root.Fail(key, fmt::format("expected an image size in px ({}), got {}", SizeLimits(), size));
  }
  return static_cast<int>(size);
}

// Both sides already within kMaxImageSide_px: the product cannot overflow.
bool ImageAreaWithinLimit(int width, int height) {
  return int64_t{width} * int64_t{height} <= kMaxImagePixels;
}

// The principal point inside the image: a real calibration never puts it outside, and
// cy = 1e9 kept the image checks busy for 23 s before they refused the image.
// `fail(index, what)` names element `index` (0 for cx, 1 for cy).
template <typename Fail>
void RequirePrincipalPointInImage(double cx, double cy, int width, int height, Fail fail) {
  const double point[2] = {cx, cy};
  const int side[2] = {width, height};
  for (size_t i = 0; i < 2; ++i) {
    if (!(point[i] >= 0.0 && point[i] <= side[i])) {
      fail(i, fmt::format("expected the principal point {} within the image (0..{} px), got {}",
                          i == 0 ? "cx" : "cy", side[i],
                          FormatDouble(point[i], i == 0 ? "cx" : "cy")));
    }
  }
}

// A lens model that folds inside the image gives part of the image no ray (issue 42 point 19:
// a calibration whose corners covered 18 of 48 cells folded 291 px from the centre):
// measure, plan and the corner path would use it without a sign.
template <typename Fail>
void RequireOneToOneOverTheImage(const CameraIntrinsics& camera, Fail fail) {
  const std::string fold = CameraModel(camera).FoldInsideImage();
  if (!fold.empty()) fail(fold + " (calibrate again with views that reach the image's corners)");
}

DistortionModel ReadDistortionModel(const YamlMap& map, const std::string& key) {
  const std::string name = map.String(key);
  const std::optional<DistortionModel> model = DistortionModelFromName(name);
  if (!model) map.Fail(key, "expected 'radtan' or 'equidistant', got '" + name + "'");
  return *model;
}

// intrinsics_covariance: n x n for fx, fy, cx, cy and the n - 4 distortion coefficients;
// symmetric, positive semi-definite, and no sigma beyond what the file could mean (a focal
// length's sigma above the focal length, a principal point's above the image's size, a
// distortion coefficient's above 1000).
void ReadIntrinsicsCovariance(const YamlMap& root, CameraIntrinsics* camera) {
  const YamlMap m = root.Map("intrinsics_covariance");
  const Matrix C = ReadMatrix(root, "intrinsics_covariance");
  const int n = 4 + static_cast<int>(camera->distortion.size());
  if (C.rows != n || C.cols != n) {
    m.Fail(
        "rows",
        fmt::format("expected {}x{} (fx, fy, cx, cy and the {} distortion coefficients), got {}x{}",
                    n, n, n - 4, C.rows, C.cols));
  }
  const Eigen::MatrixXd M =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          C.data.data(), n, n);
  const double sigma_limit[4] = {camera->K(0, 0), camera->K(1, 1),
                                 static_cast<double>(camera->width),
                                 static_cast<double>(camera->height)};
  for (int i = 0; i < n; ++i) {
    const size_t index = static_cast<size_t>(i * n + i);
    const double limit = i < 4 ? sigma_limit[i] : 1e3;
    if (!(M(i, i) >= 0.0) || !(std::sqrt(M(i, i)) <= limit)) {
      m.FailElement("data", index,
                    "expected a variance in [0, " + FormatDouble(limit * limit, "limit") +
                        "] on the diagonal, got " + FormatDouble(M(i, i), "variance"));
    }
    for (int j = 0; j < i; ++j) {
      const double tolerance = 1e-9 * std::sqrt(M(i, i) * M(j, j)) + 1e-300;
      if (!(std::abs(M(i, j) - M(j, i)) <= tolerance) ||
          !(std::abs(M(i, j)) <= std::sqrt(M(i, i) * M(j, j)) * (1 + 1e-9))) {
        m.FailElement("data", static_cast<size_t>(i * n + j),
                      "expected a symmetric covariance (|C_ij| <= sigma_i sigma_j)");
      }
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(M, Eigen::EigenvaluesOnly);
  if (eigen.eigenvalues().minCoeff() < -1e-9 * std::max(eigen.eigenvalues().maxCoeff(), 0.0)) {
    m.Fail("data", "expected a positive semi-definite covariance (an eigenvalue is " +
                       FormatDouble(eigen.eigenvalues().minCoeff(), "eigenvalue") + ")");
  }
  camera->intrinsics_covariance = M;
}

// The camera YAML OpenCV's calibration sample writes, plus an optional distortion_model.
CameraIntrinsics ParseOpenCvCamera(const YamlMap& root) {
  root.RejectCaseVariants({"image_width", "image_height", "camera_matrix", "distortion_model",
                           "distortion_coefficients", "avg_reprojection_error",
                           "intrinsics_covariance"});
  CameraIntrinsics camera;
  camera.width = ImageSize(root, "image_width");
  camera.height = ImageSize(root, "image_height");
  if (!ImageAreaWithinLimit(camera.width, camera.height)) {
    root.Fail("image_height", fmt::format("image {}x{} is too large ({})", camera.width,
                                          camera.height, SizeLimits()));
  }
  const Matrix K = ReadMatrix(root, "camera_matrix");
  if (K.rows != 3 || K.cols != 3) {
    root.Map("camera_matrix")
        .Fail("rows", fmt::format("expected a 3x3 camera matrix, got {}x{}", K.rows, K.cols));
  }
  for (size_t index : {0u, 4u}) {
    if (!(K.data[index] > 0.0)) {
      root.Map("camera_matrix")
          .FailElement("data", index, "expected a positive focal length in px (fx, fy)");
    }
  }
  RequirePrincipalPointInImage(
      K.data[2], K.data[5], camera.width, camera.height, [&](size_t i, const std::string& what) {
        root.Map("camera_matrix").FailElement("data", i == 0 ? 2 : 5, what);
      });
  RequireValue(root, K, 3, 0.0);
  RequireValue(root, K, 6, 0.0);
  RequireValue(root, K, 7, 0.0);
  RequireValue(root, K, 8, 1.0);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) camera.K(r, c) = K.data[static_cast<size_t>(3 * r + c)];
  }
  camera.distortion_model = root.Has("distortion_model")
                                ? ReadDistortionModel(root, "distortion_model")
                                : DistortionModel::kRadTan;
  const Matrix D = ReadMatrix(root, "distortion_coefficients");
  const size_t n = D.data.size();
  if ((D.rows != 1 && D.cols != 1) || n == 0 ||
      !IsSupportedDistortionCount(camera.distortion_model, static_cast<Eigen::Index>(n))) {
    root.Map("distortion_coefficients")
        .Fail("rows",
              fmt::format("expected a 1xN or Nx1 matrix with N = {} for the {} model, got {}x{}",
                          ExpectedDistortionCoefficients(camera.distortion_model),
                          ToString(camera.distortion_model), D.rows, D.cols));
  }
  camera.distortion =
      Eigen::Map<const Eigen::VectorXd>(D.data.data(), static_cast<Eigen::Index>(n));
  if (root.Has("avg_reprojection_error")) {
    const double error = root.Double("avg_reprojection_error");
    if (error < 0.0) root.Fail("avg_reprojection_error", "expected a non-negative RMS in px");
    camera.avg_reprojection_error = error;
  }
  RequireOneToOneOverTheImage(camera, [&](const std::string& why) {
    root.Fail("distortion_coefficients", why);
  });
  if (root.Has("intrinsics_covariance")) ReadIntrinsicsCovariance(root, &camera);
  return camera;
}

// One camera of a Kalibr camchain (or a file holding just that block).
CameraIntrinsics ParseKalibrCamera(const YamlMap& block) {
  block.RejectCaseVariants(
      {"camera_model", "distortion_model", "intrinsics", "distortion_coeffs", "resolution"});
  const std::string camera_model = block.String("camera_model");
  if (camera_model != "pinhole") {
    block.Fail(
        "camera_model",
        "expected 'pinhole' (the only Kalibr projection h4cal models), got '" + camera_model + "'");
  }
  CameraIntrinsics camera;
  const std::vector<int64_t> resolution = block.Ints("resolution", 2);
  for (size_t i = 0; i < 2; ++i) {
    if (resolution[i] < kMinImageSide_px || resolution[i] > kMaxImageSide_px) {
      block.FailElement("resolution", i, "expected an image size in px (" + SizeLimits() + ")");
    }
  }
  camera.width = static_cast<int>(resolution[0]);
  camera.height = static_cast<int>(resolution[1]);
  if (!ImageAreaWithinLimit(camera.width, camera.height)) {
    block.Fail("resolution", fmt::format("image {}x{} is too large ({})", camera.width,
                                         camera.height, SizeLimits()));
  }
  const std::vector<double> fu_fv_pu_pv = block.Doubles("intrinsics", 4);
  for (size_t i = 0; i < 2; ++i) {
    if (!(fu_fv_pu_pv[i] > 0.0)) {
      block.FailElement("intrinsics", i, "expected a positive focal length in px (fu, fv)");
    }
  }
  RequirePrincipalPointInImage(
      fu_fv_pu_pv[2], fu_fv_pu_pv[3], camera.width, camera.height,
      [&](size_t i, const std::string& what) { block.FailElement("intrinsics", 2 + i, what); });
  camera.K << fu_fv_pu_pv[0], 0, fu_fv_pu_pv[2], 0, fu_fv_pu_pv[1], fu_fv_pu_pv[3], 0, 0, 1;
  camera.distortion_model = ReadDistortionModel(block, "distortion_model");
  // Kalibr's radtan is OpenCV's with 4 coefficients (k1 k2 p1 p2), its equidistant
  // cv::fisheye's 4 (k1 k2 k3 k4).
  const YAML::Node coeffs = block.Get("distortion_coeffs");
  if (!coeffs.IsSequence()) block.Fail("distortion_coeffs", "expected a list of 4 numbers");
  if (coeffs.size() != 4) {
    block.Fail("distortion_coeffs",
               fmt::format("expected 4 coefficients for Kalibr's {} model, got {}",
                           ToString(camera.distortion_model), coeffs.size()));
  }
  const std::vector<double> d = block.Doubles("distortion_coeffs", 4);
  camera.distortion = Eigen::Map<const Eigen::Vector4d>(d.data());
  RequireOneToOneOverTheImage(camera, [&](const std::string& why) {
    block.Fail("distortion_coeffs", why);
  });
  return camera;
}

// cam0, cam1, ...: the camera blocks of a camchain (next to other keys, e.g. T_imu_body).
bool IsKalibrCameraName(const std::string& key) {
  return key.size() > 3 && key.rfind("cam", 0) == 0 &&
         key.find_first_not_of("0123456789", 3) == std::string::npos;
}

bool LooksLikeKalibr(const YamlMap& root) {
  return root.Has("camera_model") || root.Has("cam0") || root.Has("cam1");
}

// The camera block of a camchain: `camera` when named, else its only camN block.
YamlMap KalibrCameraBlock(const YamlMap& root, const YAML::Node& document,
                          const std::string& camera) {
  if (root.Has("camera_model")) return root;
  if (!camera.empty()) return root.Map(camera);
  std::vector<std::string> cameras;
  for (const auto& entry : document) {
    const std::string key = entry.first.as<std::string>();
    if (IsKalibrCameraName(key)) cameras.push_back(key);
  }
  if (cameras.empty()) root.Fail("cam0", "expected a Kalibr camera block (cam0, cam1, ...)");
  if (cameras.size() != 1) {
    std::string names;
    for (const auto& name : cameras) names += (names.empty() ? "" : ", ") + name;
    root.Fail(cameras.front(),
              fmt::format("a Kalibr camchain with {} cameras ({}): name one (FILE#cam1)",
                          cameras.size(), names));
  }
  return root.Map(cameras.front());
}

}  // namespace

CameraIntrinsics ParseCameraYaml(const std::string& text, const std::string& source_name,
                                 const std::string& kalibr_camera) {
  const YAML::Node document = LoadYaml(WithoutOpenCvDirective(text), source_name);
  const YamlMap root(document, source_name, "", 0);
  if (root.Has("target_type")) {
    throw FormatError(source_name, 1, "",
                      "this looks like a board file, not a camera YAML (were --board and --camera "
                      "swapped?)");
  }
  if (!kalibr_camera.empty() || LooksLikeKalibr(root)) {
    return ParseKalibrCamera(KalibrCameraBlock(root, document, kalibr_camera));
  }
  return ParseOpenCvCamera(root);
}

std::string CameraIntrinsicsProblem(const CameraIntrinsics& camera) {
  if (std::string problem = ImageSizeProblem(camera.width, camera.height); !problem.empty()) {
    return "image " + problem;
  }
  const double fx = camera.K(0, 0), fy = camera.K(1, 1);
  if (!(fx > 0.0 && fy > 0.0 && std::isfinite(fx) && std::isfinite(fy))) {
    return fmt::format("expected positive finite focal lengths fx, fy, got {}, {}", fx, fy);
  }
  if (!std::isfinite(camera.K(0, 1)) || !std::isfinite(camera.K(0, 2)) ||
      !std::isfinite(camera.K(1, 2))) {
    return "expected a finite skew and principal point";
  }
  std::string why;
  RequirePrincipalPointInImage(camera.K(0, 2), camera.K(1, 2), camera.width, camera.height,
                               [&](size_t, const std::string& what) { why = what; });
  if (!why.empty()) return why;
  const Eigen::Index n = camera.distortion.size();
  if (!IsSupportedDistortionCount(camera.distortion_model, n)) {
    return fmt::format("expected {} distortion coefficients for the {} model, got {}",
                       ExpectedDistortionCoefficients(camera.distortion_model),
                       ToString(camera.distortion_model), n);
  }
  if (!camera.distortion.allFinite()) return "expected finite distortion coefficients";
  return CameraModel(camera).FoldInsideImage();
}

CameraIntrinsics ReadCameraYaml(const std::string& path) {
  // "camchain.yaml#cam1": one camera of a Kalibr camchain.
  const size_t hash = path.rfind('#');
  if (hash != std::string::npos && IsKalibrCameraName(path.substr(hash + 1))) {
    const std::string file = path.substr(0, hash);
    return ParseCameraYaml(ReadTextFile(file), file, path.substr(hash + 1));
  }
  return ParseCameraYaml(ReadTextFile(path), path);
}

std::string FormatCameraYaml(const CameraIntrinsics& camera) {
  std::string text = fmt::format(
      "%YAML:1.0\n"
      "---\n"
      "image_width: {}\n"
      "image_height: {}\n"
      "distortion_model: {}\n",
      camera.width, camera.height, ToString(camera.distortion_model));
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
  if (camera.intrinsics_covariance) {
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C =
        *camera.intrinsics_covariance;
    text += "# fx, fy, cx, cy, then the distortion coefficients (common/formats/README.md)\n";
    text += WriteMatrix("intrinsics_covariance", static_cast<int>(C.rows()),
                        static_cast<int>(C.cols()), C.data());
  }
  return text;
}

void WriteCameraYaml(const std::string& path, const CameraIntrinsics& camera) {
  WriteTextFile(path, FormatCameraYaml(camera));
}

}  // namespace h4
