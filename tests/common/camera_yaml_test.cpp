// Camera intrinsics in OpenCV FileStorage YAML: a file OpenCV 4.6 wrote, files without
// the %YAML directive, exact round trip, malformed values with their line and field, and
// (when the tests link OpenCV) that cv::FileStorage reads what the writer writes. The
// distortion model key (radtan by default, equidistant) and Kalibr camchain files, with
// their errors.
#include "common/formats/camera_yaml.h"

#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "common/formats/csv_table.h"
#include "common/formats/number_text.h"
#include "tests/support/format_error_helpers.h"

#ifdef H4_TEST_WITH_OPENCV
#include <opencv2/core.hpp>
#endif

namespace h4 {
namespace {

// Written by cv::FileStorage (OpenCV 4.6) as the calibration sample does.
const std::string kOpenCvFile = R"(%YAML:1.0
---
calibration_time: Sat Nov 21
image_width: 1456
image_height: 1088
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1.2345678901234567e+03, 0., 7.2810000000000002e+02, 0.,
       1.2352500000000000e+03, 544., 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 5
   cols: 1
   dt: d
   data: [ -1.0000000000000001e-01, 2.0000000000000000e-02,
       1.0000000000000001e-05, -2.0000000000000001e-04, 0. ]
avg_reprojection_error: 2.5000000000000000e-01
)";

std::string CameraFileWith(const std::string& from, const std::string& to) {
  return ReplacedOnce(kOpenCvFile, from, to);
}

/// The image size and camera matrix read are those of `expected`, to the last bit.
void ExpectSizeAndMatrix(const CameraIntrinsics& camera, const CameraIntrinsics& expected) {
  EXPECT_EQ(camera.width, expected.width);
  EXPECT_EQ(camera.height, expected.height);
  EXPECT_EQ(camera.K, expected.K);
}

TEST(CameraYaml, ReadsAFileWrittenByOpenCv) {
  const CameraIntrinsics camera = ParseCameraYaml(kOpenCvFile, "cam.yaml");
  ExpectSizeAndMatrix(
      camera, CameraIntrinsics::Pinhole(1456, 1088, 1234.5678901234567, 1235.25, 728.1, 544.0));
  ASSERT_EQ(camera.distortion.size(), 5);
  EXPECT_EQ(camera.distortion[0], -0.1);
  EXPECT_EQ(camera.distortion[2], 1e-5);
  EXPECT_EQ(camera.distortion[3], -2e-4);
  EXPECT_EQ(camera.distortion[4], 0.0);
  EXPECT_EQ(camera.avg_reprojection_error, 0.25);
}

TEST(CameraYaml, AcceptsCrLfLineEndingsWithTheSameLineNumbers) {
  std::string crlf;
  for (char c : kOpenCvFile) crlf += (c == '\n') ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(ParseCameraYaml(crlf, "cam.yaml").K(0, 2), 728.1);
  const size_t at = crlf.find("dt: d");
  crlf.replace(at, 5, "dt: x");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(crlf, "c.yaml"); }, "c.yaml", 9, "camera_matrix.dt",
                        "expected 'd' or 'f'"));
}

TEST(CameraYaml, AcceptsPlainYamlAndRowVectorsAndNoRmsKey) {
  std::string text = CameraFileWith("%YAML:1.0\n---\n", "");
  text = text.substr(0, text.find("avg_reprojection_error"));
  const size_t rows = text.find("rows: 5");
  text.replace(rows, 7, "rows: 1");
  text.replace(text.find("cols: 1", rows), 7, "cols: 5");
  const CameraIntrinsics camera = ParseCameraYaml(text, "cam.yaml");
  EXPECT_EQ(camera.distortion.size(), 5);
  EXPECT_FALSE(camera.avg_reprojection_error.has_value());
}

TEST(CameraYaml, RoundTripIsExact) {
  CameraIntrinsics camera;
  camera.width = 1456;
  camera.height = 1088;
  camera.K << 1000.0 / 3, 0, 728, 0, 1001.0 / 7, 544.5, 0, 0, 1;
  camera.distortion.resize(8);
  camera.distortion << -0.1, 0.02, 1e-5, -2e-4, 1.0 / 3, 0, 0, 1e-20;
  camera.avg_reprojection_error = 0.1 + 0.2;
  const std::string text = FormatCameraYaml(camera);
  EXPECT_EQ(text.rfind("%YAML:1.0\n---\n", 0), 0u);
  const std::string path = TempPath("camera.yaml");
  WriteCameraYaml(path, camera);
  const CameraIntrinsics back = ReadCameraYaml(path);
  EXPECT_EQ(back.width, camera.width);
  EXPECT_EQ(back.height, camera.height);
  EXPECT_EQ(back.K, camera.K);
  EXPECT_EQ(back.distortion, camera.distortion);
  EXPECT_EQ(back.avg_reprojection_error, camera.avg_reprojection_error);
}

// An edit of kOpenCvFile (`from` replaced by `to`) and what its FormatError must name.
struct CameraFileEdit {
  std::string from;
  std::string to;
  int line = 0;
  std::string field;
  std::string expected_text;
};

// For each edit: the edited file read as "c.yaml" fails as ExpectEachFailsWith checks.
void ExpectEachEditFails(const std::vector<CameraFileEdit>& edits) {
  std::vector<MalformedInput> inputs;
  for (const CameraFileEdit& edit : edits) {
    inputs.push_back(
        {CameraFileWith(edit.from, edit.to), edit.line, edit.field, edit.expected_text});
  }
  const auto parse = [](const std::string& text, const std::string& source) {
    return ParseCameraYaml(text, source);
  };
  ExpectEachFailsWith(parse, "c.yaml", inputs);
}

TEST(CameraYamlErrors, NameLineAndField) {
  // Line numbers are those of the file, the %YAML line included.
  ExpectEachEditFails({
      {"image_width: 1456", "image_width: 0", 4, "image_width", "expected an image size in px"},
      {"image_height: 1088", "image_height: 10.5", 5, "image_height", "expected an integer"},
      {"image_height: 1088\n", "", 0, "image_height", "missing key"},
      {"dt: d", "dt: u", 9, "camera_matrix.dt", "expected 'd' or 'f'"},
      {"0., 0., 1. ]", "0., 1. ]", 10, "camera_matrix.data", "list of 9 numbers, got a list of 8"},
      {"544., 0., 0., 1.", "544., 0., 0., 2.", 11, "camera_matrix.data[8]", "expected 1"},
      {"1.2352500000000000e+03", "-1.23525e+03", 11, "camera_matrix.data[4]",
       "positive focal length"},
      {"544.,", "oops,", 11, "camera_matrix.data[5]", "expected a number, got 'oops'"},
      {"rows: 5", "rows: 6", 16, "distortion_coefficients.data", "list of 6"},
      {"dt: d", "dtype: d", 9, "camera_matrix.dtype", "unknown key"},
      {"rows: 3", "rows: 2", 10, "camera_matrix.data", "list of 6"},
      {"avg_reprojection_error: 2.5000000000000000e-01", "avg_reprojection_error: -1", 18,
       "avg_reprojection_error", "non-negative"},
      {"   cols: 3", "     cols: 3", 8, "", "invalid YAML"},
  });
}

// intrinsics_covariance: 9 x 9 (fx, fy, cx, cy, five coefficients), kept exactly; a wrong
// size, an asymmetric, negative or non-positive-semi-definite matrix is refused by element.
std::string CovarianceKey(const std::vector<double>& data, int n = 9) {
  std::string text = fmt::format(
      "intrinsics_covariance: !!opencv-matrix\n   rows: {0}\n   cols: {0}\n   dt: d\n   data: [ ",
      n);
  for (size_t i = 0; i < data.size(); ++i) text += (i ? ", " : "") + FormatDouble(data[i], "x");
  return text + " ]\n";
}

std::vector<double> DiagonalCovariance() {
  std::vector<double> c(81, 0.0);
  const double sigma[9] = {0.4, 0.4, 0.5, 0.4, 1e-3, 5e-3, 1e-5, 1e-5, 1e-2};
  for (int i = 0; i < 9; ++i) c[static_cast<size_t>(10 * i)] = sigma[i] * sigma[i];
  return c;
}

TEST(CameraYaml, KeepsTheIntrinsicsCovariance) {
  std::vector<double> c = DiagonalCovariance();
  c[1] = c[9] = 0.9 * 0.4 * 0.4;  // fx and fy correlated
  const CameraIntrinsics camera = ParseCameraYaml(kOpenCvFile + CovarianceKey(c), "c.yaml");
  ASSERT_TRUE(camera.intrinsics_covariance.has_value());
  EXPECT_DOUBLE_EQ((*camera.intrinsics_covariance)(0, 1), 0.9 * 0.4 * 0.4);
  const CameraIntrinsics back = ParseCameraYaml(FormatCameraYaml(camera), "back.yaml");
  EXPECT_EQ(*back.intrinsics_covariance, *camera.intrinsics_covariance);
}

TEST(CameraYamlErrors, TheIntrinsicsCovarianceIsChecked) {
  EXPECT_TRUE(FailsWith(
      [] {
        ParseCameraYaml(kOpenCvFile + CovarianceKey(std::vector<double>(64, 0.0), 8), "c.yaml");
      },
      "c.yaml", 20, "intrinsics_covariance.rows", "expected 9x9"));
  std::vector<double> negative = DiagonalCovariance();
  negative[20] = -1.0;
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kOpenCvFile + CovarianceKey(negative), "c.yaml"); },
                        "c.yaml", 23, "intrinsics_covariance.data[20]", "variance in [0"));
  std::vector<double> huge = DiagonalCovariance();
  huge[0] = 1e20;  // a focal length's sigma of 1e10 px
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kOpenCvFile + CovarianceKey(huge), "c.yaml"); },
                        "c.yaml", 23, "intrinsics_covariance.data[0]", "variance in [0"));
  std::vector<double> asymmetric = DiagonalCovariance();
  asymmetric[1] = 0.01;
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kOpenCvFile + CovarianceKey(asymmetric), "c.yaml"); },
                        "c.yaml", 23, "intrinsics_covariance.data[9]", "symmetric"));
  std::vector<double> indefinite = DiagonalCovariance();
  // |rho| <= 1 pairwise, yet fx, fy, cx at correlations -1, -1, -1: not a covariance.
  const double s0 = 0.4, s1 = 0.4, s2 = 0.5;
  indefinite[1] = indefinite[9] = -s0 * s1;
  indefinite[2] = indefinite[18] = -s0 * s2;
  indefinite[11] = indefinite[19] = -s1 * s2;
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kOpenCvFile + CovarianceKey(indefinite), "c.yaml"); },
                        "c.yaml", 23, "intrinsics_covariance.data", "positive semi-definite"));
}

// A 20000 x 20000 camera made `measure` and `render` run for minutes and take gigabytes:
// the reader refuses it before anything is sized from it.
TEST(CameraYamlErrors, ImageSizeIsLimitedBeforeAnythingIsAllocated) {
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("image_width: 1456", "image_width: 20000"), "c.yaml"); },
      "c.yaml", 4, "image_width", "32..16384 px a side"));
  EXPECT_TRUE(FailsWith(
      [] {
        ParseCameraYaml(CameraFileWith("image_height: 1088", "image_height: 16385"), "c.yaml");
      },
      "c.yaml", 5, "image_height", "got 16385"));
  // Each side within the limit, the area not: 8192 x 8192 = 64 Mpx.
  const std::string wide = CameraFileWith("image_width: 1456\nimage_height: 1088",
                                          "image_width: 8192\nimage_height: 8192");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(wide, "c.yaml"); }, "c.yaml", 5, "image_height",
                        "8192x8192 is too large"));
  // The largest accepted: a side at the limit, the area at the limit.
  const std::string largest = CameraFileWith("image_width: 1456\nimage_height: 1088",
                                             "image_width: 16384\nimage_height: 1024");
  EXPECT_EQ(ParseCameraYaml(largest, "c.yaml").width, kMaxImageSide_px);
}

// Issue 42 point 1: a camera file with image_height 4 was accepted, and libapriltag segfaults
// on an image 4 px high (h4cam run died on its first measurement). Below kMinImageSide_px a
// side, the file is refused naming the field; at it, it is read.
TEST(CameraYamlErrors, ImageSideBelowTheDetectorsSmallestIsRefused) {
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("image_height: 1088", "image_height: 4"), "c.yaml"); },
      "c.yaml", 5, "image_height", "got 4"));
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("image_width: 1456", "image_width: 31"), "c.yaml"); },
      "c.yaml", 4, "image_width", "32..16384 px a side"));
  const std::string smallest =
      CameraFileWith("image_width: 1456\nimage_height: 1088", "image_width: 32\nimage_height: 32");
  // The principal point must lie in the image: put it there.
  std::string text = smallest;
  text.replace(text.find("7.2810000000000002e+02"), 22, "16.");
  text.replace(text.find("544.,"), 5, "16.,");
  EXPECT_EQ(ParseCameraYaml(text, "c.yaml").height, kMinImageSide_px);
}

// Issue 42 point 19: a camera file whose lens model folds inside the image was read and
// used by measure, plan and identify. k1 -5 folds about 213 px from the principal point
// of this 1456 x 1088 camera; k1 -0.1 (the file as written) does not fold at all.
TEST(CameraYamlErrors, ALensModelThatFoldsInsideTheImageIsRefused) {
  const std::string folding = CameraFileWith("data: [ -1.0000000000000001e-01,", "data: [ -5.,");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(folding, "c.yaml"); }, "c.yaml", 12,
                        "distortion_coefficients", "the lens model folds about"));
  const std::string kalibr =
      "camera_model: pinhole\ndistortion_model: radtan\nintrinsics: [800, 800, 512, 384]\n"
      "distortion_coeffs: [-0.8, 0, 0, 0]\nresolution: [1024, 768]\n";
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kalibr, "k.yaml"); }, "k.yaml", 4,
                        "distortion_coeffs", "the lens model folds about"));
  EXPECT_NO_THROW(ParseCameraYaml(kOpenCvFile, "c.yaml"));
}

TEST(CameraYamlErrors, DistortionCountMustBe4Or5Or8) {
  // 2 x 2 holds 4 values but is not a vector.
  const std::string text = CameraFileWith("rows: 5\n   cols: 1", "rows: 2\n   cols: 2");
  std::string four = text;
  four.replace(four.find(", 0. ]"), 6, " ]");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(four, "c.yaml"); }, "c.yaml", 13,
                        "distortion_coefficients.rows", "1xN or Nx1"));
}

TEST(CameraYaml, AFileWithoutDistortionModelIsRadtan) {
  EXPECT_EQ(ParseCameraYaml(kOpenCvFile, "cam.yaml").distortion_model, DistortionModel::kRadTan);
  const std::string text =
      CameraFileWith("image_height: 1088\n", "image_height: 1088\ndistortion_model: radtan\n");
  EXPECT_EQ(ParseCameraYaml(text, "cam.yaml").distortion_model, DistortionModel::kRadTan);
}

// The same file for a fisheye lens: distortion_model and 4 coefficients k1..k4.
std::string EquidistantFile() {
  std::string text =
      CameraFileWith("image_height: 1088\n", "image_height: 1088\ndistortion_model: equidistant\n");
  text.replace(text.find("rows: 5"), 7, "rows: 4");
  text.replace(text.find(", 0. ]"), 6, " ]");
  return text;
}

TEST(CameraYaml, ReadsAndWritesTheEquidistantModel) {
  const CameraIntrinsics camera = ParseCameraYaml(EquidistantFile(), "fisheye.yaml");
  EXPECT_EQ(camera.distortion_model, DistortionModel::kEquidistant);
  ASSERT_EQ(camera.distortion.size(), 4);
  EXPECT_EQ(camera.distortion[3], -2e-4);
  const std::string text = FormatCameraYaml(camera);
  EXPECT_NE(text.find("\ndistortion_model: equidistant\n"), std::string::npos) << text;
  const CameraIntrinsics back = ParseCameraYaml(text, "written.yaml");
  EXPECT_EQ(back.distortion_model, DistortionModel::kEquidistant);
  EXPECT_EQ(back.distortion, camera.distortion);
  EXPECT_EQ(back.K, camera.K);
}

TEST(CameraYamlErrors, UnknownModelAndWrongCountForTheModelNameTheField) {
  EXPECT_TRUE(FailsWith(
      [] {
        ParseCameraYaml(CameraFileWith("image_height: 1088\n",
                                       "image_height: 1088\ndistortion_model: fisheye\n"),
                        "c.yaml");
      },
      "c.yaml", 6, "distortion_model", "expected 'radtan' or 'equidistant', got 'fisheye'"));
  // Five coefficients are a radtan vector, not an equidistant one.
  std::string five =
      CameraFileWith("image_height: 1088\n", "image_height: 1088\ndistortion_model: equidistant\n");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(five, "c.yaml"); }, "c.yaml", 14,
                        "distortion_coefficients.rows",
                        "N = 4 (k1 k2 k3 k4) for the equidistant model, got 5x1"));
}

// Kalibr's camchain for the EuRoC MAV dataset's cam0 (kalibr_calibrate_cameras output).
const std::string kKalibrCamchain = R"(cam0:
  cam_overlaps: [1]
  camera_model: pinhole
  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
  distortion_model: radtan
  intrinsics: [458.654, 457.296, 367.215, 248.375]
  resolution: [752, 480]
  rostopic: /cam0/image_raw
  T_cam_imu:
  - [0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975]
  - [0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768]
  - [-0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949]
  - [0.0, 0.0, 0.0, 1.0]
)";

const std::string kKalibrFisheye = R"(cam1:
  camera_model: pinhole
  distortion_coeffs: [0.0034, 0.0339, -0.0412, 0.0143]
  distortion_model: equidistant
  intrinsics: [190.97, 190.97, 254.93, 256.89]
  resolution: [512, 512]
)";

TEST(CameraYaml, ReadsAKalibrCamchain) {
  const CameraIntrinsics camera = ParseCameraYaml(kKalibrCamchain, "camchain.yaml");
  ExpectSizeAndMatrix(camera,
                      CameraIntrinsics::Pinhole(752, 480, 458.654, 457.296, 367.215, 248.375));
  EXPECT_EQ(camera.distortion_model, DistortionModel::kRadTan);
  ASSERT_EQ(camera.distortion.size(), 4);
  EXPECT_EQ(camera.distortion[0], -0.28340811);
  EXPECT_EQ(camera.distortion[3], 1.76187114e-05);
  EXPECT_FALSE(camera.avg_reprojection_error.has_value());

  const CameraIntrinsics fisheye = ParseCameraYaml(kKalibrFisheye, "tum.yaml");
  EXPECT_EQ(fisheye.distortion_model, DistortionModel::kEquidistant);
  EXPECT_EQ(fisheye.distortion[1], 0.0339);
  EXPECT_EQ(fisheye.K(1, 2), 256.89);
}

TEST(CameraYaml, ReadsOneCameraOfAKalibrCamchainByName) {
  const std::string two = kKalibrCamchain + kKalibrFisheye;
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(two, "chain.yaml"); }, "chain.yaml", 2, "cam0",
                        "2 cameras (cam0, cam1): name one (FILE#cam1)"));
  EXPECT_EQ(ParseCameraYaml(two, "chain.yaml", "cam1").width, 512);
  const std::string path = TempPath("camchain.yaml");
  WriteTextFile(path, two);
  EXPECT_EQ(ReadCameraYaml(path + "#cam1").distortion_model, DistortionModel::kEquidistant);
  EXPECT_EQ(ReadCameraYaml(path + "#cam0").width, 752);
  EXPECT_TRUE(FailsWith([&] { ReadCameraYaml(path + "#cam2"); }, path, 0, "cam2", "missing key"));
}

// issue 27 point 7: cy = 1e9 read, and the image checks took 23 s before refusing the
// image. A principal point outside the image is refused naming the element.
TEST(CameraYamlErrors, APrincipalPointOutsideTheImageNamesTheElement) {
  EXPECT_TRUE(
      FailsWith([] { ParseCameraYaml(CameraFileWith("544.", "1e9"), "cam.yaml"); }, "cam.yaml", 11,
                "camera_matrix.data[5]",
                "expected the principal point cy within the image (0..1088 px), got 1e+09"));
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("7.2810000000000002e+02", "-1."), "cam.yaml"); },
      "cam.yaml", 10, "camera_matrix.data[2]", "principal point cx"));
  std::string kalibr = kKalibrCamchain;
  kalibr.replace(kalibr.find("248.375"), 7, "1e9");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(kalibr, "k.yaml"); }, "k.yaml", 6,
                        "cam0.intrinsics[3]", "principal point cy"));
}

TEST(CameraYamlErrors, KalibrFieldsAreCheckedAndNamed) {
  const auto with = [](const std::string& from, const std::string& to) {
    std::string text = kKalibrCamchain;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  EXPECT_TRUE(FailsWith(
      [&] { ParseCameraYaml(with("camera_model: pinhole", "camera_model: omni"), "k.yaml"); },
      "k.yaml", 3, "cam0.camera_model", "expected 'pinhole'"));
  EXPECT_TRUE(FailsWith(
      [&] { ParseCameraYaml(with("distortion_model: radtan", "distortion_model: fov"), "k.yaml"); },
      "k.yaml", 5, "cam0.distortion_model", "got 'fov'"));
  EXPECT_TRUE(FailsWith(
      [&] { ParseCameraYaml(with(", 1.76187114e-05]", ", 1.7e-05, 0.0]"), "k.yaml"); }, "k.yaml", 4,
      "cam0.distortion_coeffs", "expected 4 coefficients for Kalibr's radtan model, got 5"));
  EXPECT_TRUE(
      FailsWith([&] { ParseCameraYaml(with("[458.654, 457.296", "[-458.654, 457.296"), "k.yaml"); },
                "k.yaml", 6, "cam0.intrinsics[0]", "positive focal length"));
  EXPECT_TRUE(FailsWith(
      [&] { ParseCameraYaml(with("resolution: [752, 480]", "resolution: [752]"), "k.yaml"); },
      "k.yaml", 7, "cam0.resolution", "2"));
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(with("  resolution: [752, 480]\n", ""), "k.yaml"); },
                        "k.yaml", 1, "cam0.resolution", "missing key"));
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseCameraYaml(with("resolution: [752, 480]", "resolution: [20000, 20000]"), "k.yaml");
      },
      "k.yaml", 7, "cam0.resolution[0]", "16384 px a side"));
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseCameraYaml(with("resolution: [752, 480]", "resolution: [16000, 16000]"), "k.yaml");
      },
      "k.yaml", 7, "cam0.resolution", "16000x16000 is too large"));
}

#ifdef H4_TEST_WITH_OPENCV
TEST(CameraYaml, OpenCvReadsWhatTheWriterWrites) {
  CameraIntrinsics camera;
  camera.width = 640;
  camera.height = 480;
  camera.K << 500, 0, 320, 0, 500.25, 240, 0, 0, 1;  // integers must still read as reals
  camera.distortion.resize(5);
  camera.distortion << -0.1, 0.02, 1e-5, -2e-4, 0;
  camera.avg_reprojection_error = 0.0;
  cv::FileStorage fs(FormatCameraYaml(camera), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 640);
  EXPECT_EQ(static_cast<int>(fs["image_height"]), 480);
  cv::Mat K, D;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  ASSERT_EQ(K.type(), CV_64F);
  ASSERT_EQ(K.rows, 3);
  ASSERT_EQ(K.cols, 3);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(K.at<double>(r, c), camera.K(r, c));
  }
  ASSERT_EQ(D.total(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(D.at<double>(i), camera.distortion[i]);
  EXPECT_TRUE(fs["avg_reprojection_error"].isReal());
  EXPECT_EQ(static_cast<double>(fs["avg_reprojection_error"]), 0.0);
}
#endif

// --board and --camera swapped: one line that names the mix-up (issue 26 point 8).
TEST(CameraYaml, ABoardFileGivenAsTheCameraSaysTheyWereSwapped) {
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml("target_type: aprilgrid\ntagCols: 6\ntagRows: 6\n", "board.yaml"); },
      "board.yaml", 1, "",
      "this looks like a board file, not a camera YAML (were --board and --camera swapped?)"));
}

}  // namespace
}  // namespace h4
