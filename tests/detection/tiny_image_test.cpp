// Issue 42 point 1: libapriltag segfaults on an image 4 px high or less, reached through
// measure, preview, calibrate-intrinsics and the camera service (a camera file with
// image_height 4 was accepted). The detector's entry refuses what it cannot handle
// (common/formats/image_size.h): no detection from an image under the smallest side, and a
// board detector for a camera of that size says why instead of detecting.
#include <utility>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "common/formats/image_size.h"
#include "firmware/detection/apriltag_detector.h"
#include "firmware/detection/board_detector.h"

namespace h4::cam {
namespace {

BoardSpec DemoAprilGrid() {
  AprilGridSpec grid;
  grid.layout = AprilGridLayout::kH4Legacy;
  return grid;
}

TEST(TinyImage, TheTagDetectorFindsNothingInAnImageUnderTheSmallestSideAndDoesNotCrash) {
  const AprilTagDetector detector;
  ASSERT_TRUE(detector.ok()) << detector.error();
  for (const cv::Size size : {cv::Size(64, 3), cv::Size(64, 4), cv::Size(3, 64), cv::Size(1, 1),
                              cv::Size(64, kMinImageSide_px - 1)}) {
    cv::Mat image(size, CV_8UC1);
    cv::randu(image, 0, 255);
    EXPECT_TRUE(detector.Detect(image).empty()) << size;
    EXPECT_TRUE(detector.DetectCandidates(image).empty()) << size;
  }
  // At the smallest side, libapriltag runs (and finds no tag in noise).
  cv::Mat smallest(kMinImageSide_px, kMinImageSide_px, CV_8UC1);
  cv::randu(smallest, 0, 255);
  EXPECT_TRUE(detector.Detect(smallest).empty());
}

TEST(TinyImage, ABoardDetectorForACameraUnderTheSmallestSideSaysWhy) {
  for (const auto& [width, height] : {std::pair{64, 4}, std::pair{4, 64}, std::pair{20000, 64}}) {
    const CameraIntrinsics camera =
        CameraIntrinsics::Pinhole(width, height, 100.0, 100.0, 0.5 * width, 0.5 * height);
    const BoardDetector detector(DemoAprilGrid(), camera);
    EXPECT_FALSE(detector.ok()) << width << "x" << height;
    EXPECT_NE(detector.error().find(fmt::format("camera image size {}x{} px: expected 32..16384",
                                                width, height)),
              std::string::npos)
        << detector.error();
    cv::Mat image(height, width, CV_8UC1, cv::Scalar(128));
    EXPECT_TRUE(detector.Detect(image).corners.empty());
  }
}

}  // namespace
}  // namespace h4::cam
