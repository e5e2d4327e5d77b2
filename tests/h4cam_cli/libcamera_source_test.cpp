// The libcamera frame source without hardware: luma copy with a stride, timestamp
// mapping, the lifecycle state machine, and how it fails when there is no camera. The
// tests that need a camera skip themselves (GTEST_SKIP) when libcamera lists none.
#include "firmware/sources/libcamera_source.h"

#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <time.h>

#include "firmware/cli/list_cameras_command.h"
#include "firmware/sources/libcamera_compat.h"
#include "firmware/sources/libcamera_frame.h"
#include "firmware/sources/libcamera_manager.h"
#include "tests/support/options_check.h"

namespace h4::cam {
namespace {

bool HaveCamera() {
  std::vector<CameraInfo> cameras;
  std::string error;
  return ListCameras(&cameras, &error) && !cameras.empty();
}

TEST(LumaPlaneCopy, DropsStridePaddingAndKeepsEveryPixel) {
  // A 5x3 image in a plane with 8-byte rows: padding bytes are 0xEE and must not appear.
  const int width = 5, height = 3, stride = 8;
  std::vector<uint8_t> plane(static_cast<size_t>(stride * height), 0xEE);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      plane[static_cast<size_t>(y * stride + x)] = uint8_t(10 * y + x);
  }
  cv::Mat image;
  std::string error;
  ASSERT_TRUE(CopyLumaPlane(plane.data(), plane.size(), width, height, stride, &image, &error))
      << error;
  ASSERT_EQ(image.type(), CV_8UC1);
  ASSERT_EQ(image.cols, width);
  ASSERT_EQ(image.rows, height);
  EXPECT_TRUE(image.isContinuous());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) EXPECT_EQ(image.at<uint8_t>(y, x), 10 * y + x) << x << "," << y;
  }
}

TEST(LumaPlaneCopy, UsesOnlyTheYPlaneOfAYuv420Buffer) {
  // YUV420: Y (stride 8) followed by U and V planes full of 0x80; only Y is copied, and
  // the last Y row may end without padding.
  const int width = 6, height = 4, stride = 8;
  std::vector<uint8_t> buffer(static_cast<size_t>(stride * height * 3 / 2), 0x80);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      buffer[static_cast<size_t>(y * stride + x)] = uint8_t(y * width + x);
  }
  cv::Mat image;
  std::string error;
  const size_t y_bytes = static_cast<size_t>(stride * (height - 1) + width);
  ASSERT_TRUE(CopyLumaPlane(buffer.data(), y_bytes, width, height, stride, &image, &error))
      << error;
  EXPECT_EQ(image.at<uint8_t>(3, 5), 3 * 6 + 5);
  EXPECT_EQ(cv::countNonZero(image == 0x80), 0);
}

TEST(LumaPlaneCopy, RejectsAStrideShorterThanARowAndATruncatedPlane) {
  std::vector<uint8_t> plane(100, 0);
  cv::Mat image;
  std::string error;
  EXPECT_FALSE(CopyLumaPlane(plane.data(), plane.size(), 10, 5, 8, &image, &error));
  EXPECT_NE(error.find("stride 8"), std::string::npos) << error;
  EXPECT_FALSE(CopyLumaPlane(plane.data(), plane.size(), 10, 11, 10, &image, &error));
  EXPECT_NE(error.find("expected at least 110"), std::string::npos) << error;
  EXPECT_FALSE(CopyLumaPlane(nullptr, 0, 10, 10, 10, &image, &error));
  EXPECT_TRUE(image.empty());
}

TEST(SensorTimestamp, MapsNanosecondsToMicrosecondsSinceTheEpochRoundingDown) {
  const ClockOffset offset{1'700'000'000'000'000'000, 0};  // realtime - monotonic
  EXPECT_EQ(SensorNsToUtime(123'456'789'999, offset), 1'700'000'123'456'789);
  EXPECT_EQ(SensorNsToUtime(0, ClockOffset{-1'500, 0}), -2);  // floor, not toward zero
}

TEST(SensorTimestamp, MonotonicNowMapsToRealtimeNow) {
  for (const auto& [sensor_clock, clock] : {std::pair{SensorClock::kMonotonic, CLOCK_MONOTONIC},
                                            std::pair{SensorClock::kBoottime, CLOCK_BOOTTIME}}) {
    const ClockOffset offset = MeasureClockOffset(sensor_clock);
    EXPECT_LT(offset.uncertainty_ns, 1'000'000);
    const int64_t sensor_ns = ReadClockNs(clock);
    const int64_t realtime_us = ReadClockNs(CLOCK_REALTIME) / 1000;
    // Both reads happen within a few microseconds; 2 ms leaves room for a busy machine.
    EXPECT_NEAR(static_cast<double>(SensorNsToUtime(sensor_ns, offset)),
                static_cast<double>(realtime_us), 2000.0);
  }
}

TEST(LibcameraCompat, ReportsTheVersionOfTheHeaders) {
  EXPECT_EQ(compat::CompiledLibcameraVersion(),
            fmt::format("{}.{}.{}", LIBCAMERA_VERSION_MAJOR, LIBCAMERA_VERSION_MINOR,
                        LIBCAMERA_VERSION_PATCH));
}

TEST(LibcameraSourceLifecycle, StartBeforeConfigureFailsWithAnError) {
  LibcameraSource source({});
  EXPECT_FALSE(source.Start());
  EXPECT_NE(source.error().find("Start() called while the camera is closed; expected configured"),
            std::string::npos)
      << source.error();
  EXPECT_FALSE(source.Configure());
  EXPECT_NE(source.error().find("Configure() called while the camera is closed"),
            std::string::npos);
  EXPECT_FALSE(source.Next(std::chrono::milliseconds(10)).has_value());
  EXPECT_NE(source.error().find("Next() called"), std::string::npos);
  source.Stop();  // harmless in any state
  source.Close();
  EXPECT_EQ(source.state(), LibcameraSource::State::kClosed);
}

TEST(LibcameraSourceLifecycle, InvalidOptionsAreRejectedByOpen) {
  LibcameraSourceOptions options;
  options.analogue_gain = 0.5f;
  EXPECT_TRUE(RefusedNaming(options, "analogue gain"));
  LibcameraSource source(options);
  EXPECT_FALSE(source.Open());
  EXPECT_NE(source.error().find("analogue gain"), std::string::npos) << source.error();
}

TEST(LibcameraSourceWithoutCamera, OpeningAMissingIdFailsNamingTheId) {
  LibcameraSourceOptions options;
  options.camera_id = "/base/soc/i2c0mux/i2c@1/no-such-sensor@10";
  LibcameraSource source(options);
  EXPECT_FALSE(source.Open());
  EXPECT_NE(source.error().find("no camera with id '" + options.camera_id + "'"), std::string::npos)
      << source.error();
  EXPECT_EQ(source.state(), LibcameraSource::State::kClosed);
  // A failed open leaves a source that can be closed and opened again.
  source.Close();
  EXPECT_FALSE(source.Open());
}

TEST(LibcameraSourceWithoutCamera, OpeningTheFirstCameraFailsClearlyWhenThereIsNone) {
  if (HaveCamera()) GTEST_SKIP() << "a camera is connected; this test is for machines without";
  LibcameraSource source({});
  EXPECT_FALSE(source.Open());
  EXPECT_NE(source.error().find("no cameras found"), std::string::npos) << source.error();
}

TEST(ListCamerasCommand, SaysNoCamerasFoundAndSucceedsOnAMachineWithoutOne) {
  if (HaveCamera()) GTEST_SKIP() << "a camera is connected; this test is for machines without";
  std::ostringstream out;
  EXPECT_EQ(RunListCameras(out), 0);
  EXPECT_EQ(out.str().rfind("no cameras found", 0), 0u) << out.str();
}

TEST(ListCamerasCommand, PrintsOneLinePerCameraStartingWithItsId) {
  std::vector<CameraInfo> cameras;
  std::string error;
  ASSERT_TRUE(ListCameras(&cameras, &error)) << error;
  if (cameras.empty()) GTEST_SKIP() << "no camera connected (hardware test)";
  std::ostringstream out;
  EXPECT_EQ(RunListCameras(out), 0);
  std::istringstream lines(out.str());
  for (const auto& camera : cameras) {
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line.rfind(camera.id, 0), 0u) << line;
  }
}

// Needs a camera (skipped otherwise): the full lifecycle delivers grey frames of the
// configured size with increasing, current timestamps.
TEST(LibcameraSourceHardware, DeliversTimestampedFramesAndRestartsCleanly) {
  if (!HaveCamera()) GTEST_SKIP() << "no camera connected (hardware test)";
  LibcameraSource source({});
  ASSERT_TRUE(source.Open()) << source.error();
  ASSERT_TRUE(source.Configure()) << source.error();
  for (int round = 0; round < 2; ++round) {  // stop/start twice: requests are reused
    ASSERT_TRUE(source.Start()) << source.error();
    int64_t last_utime = 0;
    for (int i = 0; i < 5; ++i) {
      const auto frame = source.Next(std::chrono::seconds(3));
      ASSERT_TRUE(frame.has_value()) << source.error();
      EXPECT_EQ(frame->image.type(), CV_8UC1);
      EXPECT_EQ(frame->image.cols, source.width());
      EXPECT_GT(frame->utime, last_utime);
      EXPECT_NEAR(static_cast<double>(frame->utime),
                  static_cast<double>(ReadClockNs(CLOCK_REALTIME) / 1000), 1e6);
      last_utime = frame->utime;
    }
    source.Stop();
  }
  source.Close();
  EXPECT_EQ(source.restarts(), 0);
}

}  // namespace
}  // namespace h4::cam
