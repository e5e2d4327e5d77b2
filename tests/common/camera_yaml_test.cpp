// Camera intrinsics in OpenCV FileStorage YAML: a file OpenCV 4.6 wrote, files without
// the %YAML directive, exact round trip, malformed values with their line and field, and
// (when the tests link OpenCV) that cv::FileStorage reads what the writer writes.
#include "common/formats/camera_yaml.h"

#include <gtest/gtest.h>

#include "tests/common/format_error_helpers.h"

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
  std::string text = kOpenCvFile;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(CameraYaml, ReadsAFileWrittenByOpenCv) {
  const CameraIntrinsics camera = ParseCameraYaml(kOpenCvFile, "cam.yaml");
  EXPECT_EQ(camera.width, 1456);
  EXPECT_EQ(camera.height, 1088);
  Eigen::Matrix3d K;
  K << 1234.5678901234567, 0, 728.1, 0, 1235.25, 544.0, 0, 0, 1;
  EXPECT_EQ(camera.K, K);
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

TEST(CameraYamlErrors, NameLineAndField) {
  // Line numbers are those of the file, the %YAML line included.
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("image_width: 1456", "image_width: 0"), "c.yaml"); },
      "c.yaml", 4, "image_width", "positive image size"));
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("image_height: 1088", "image_height: 10.5"), "c.yaml"); },
      "c.yaml", 5, "image_height", "expected an integer"));
  EXPECT_TRUE(
      FailsWith([] { ParseCameraYaml(CameraFileWith("image_height: 1088\n", ""), "c.yaml"); },
                "c.yaml", 0, "image_height", "missing key"));
  EXPECT_TRUE(FailsWith([] { ParseCameraYaml(CameraFileWith("dt: d", "dt: u"), "c.yaml"); },
                        "c.yaml", 9, "camera_matrix.dt", "expected 'd' or 'f'"));
  EXPECT_TRUE(
      FailsWith([] { ParseCameraYaml(CameraFileWith("0., 0., 1. ]", "0., 1. ]"), "c.yaml"); },
                "c.yaml", 10, "camera_matrix.data", "list of 9 numbers, got a list of 8"));
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("544., 0., 0., 1.", "544., 0., 0., 2."), "c.yaml"); },
      "c.yaml", 11, "camera_matrix.data[8]", "expected 1"));
  EXPECT_TRUE(FailsWith(
      [] { ParseCameraYaml(CameraFileWith("1.2352500000000000e+03", "-1.23525e+03"), "c.yaml"); },
      "c.yaml", 11, "camera_matrix.data[4]", "positive focal length"));
  EXPECT_TRUE(FailsWith([] { ParseCameraYaml(CameraFileWith("544.,", "oops,"), "c.yaml"); },
                        "c.yaml", 11, "camera_matrix.data[5]", "expected a number, got 'oops'"));
  EXPECT_TRUE(FailsWith([] { ParseCameraYaml(CameraFileWith("rows: 5", "rows: 6"), "c.yaml"); },
                        "c.yaml", 16, "distortion_coefficients.data", "list of 6"));
  EXPECT_TRUE(FailsWith([] { ParseCameraYaml(CameraFileWith("dt: d", "dtype: d"), "c.yaml"); },
                        "c.yaml", 9, "camera_matrix.dtype", "unknown key"));
  EXPECT_TRUE(FailsWith([] { ParseCameraYaml(CameraFileWith("rows: 3", "rows: 2"), "c.yaml"); },
                        "c.yaml", 10, "camera_matrix.data", "list of 6"));
  EXPECT_TRUE(FailsWith(
      [] {
        ParseCameraYaml(CameraFileWith("avg_reprojection_error: 2.5000000000000000e-01",
                                       "avg_reprojection_error: -1"),
                        "c.yaml");
      },
      "c.yaml", 18, "avg_reprojection_error", "non-negative"));
  EXPECT_TRUE(
      FailsWith([] { ParseCameraYaml(CameraFileWith("   cols: 3", "     cols: 3"), "c.yaml"); },
                "c.yaml", 8, "", "invalid YAML"));
}

TEST(CameraYamlErrors, DistortionCountMustBe4Or5Or8) {
  // 2 x 2 holds 4 values but is not a vector.
  const std::string text = CameraFileWith("rows: 5\n   cols: 1", "rows: 2\n   cols: 2");
  std::string four = text;
  four.replace(four.find(", 0. ]"), 6, " ]");
  EXPECT_TRUE(FailsWith([&] { ParseCameraYaml(four, "c.yaml"); }, "c.yaml", 13,
                        "distortion_coefficients.rows", "1xN or Nx1"));
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

}  // namespace
}  // namespace h4
