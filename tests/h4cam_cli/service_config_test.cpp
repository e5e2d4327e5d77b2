// The camera service configuration: the packaged file parses to the values it states,
// errors name the file, the line and the field, and command-line flags override the file.
#include "firmware/service/service_config.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "common/formats/format_error.h"
#include "firmware/cli/run_command.h"

namespace h4::cam {
namespace {

TEST(ServiceConfigTest, PackagedConfigurationGivesItsStatedValues) {
  const ServiceConfig c = ReadServiceConfig(H4_SOURCE_DIR "/firmware/packaging/h4cam.yaml");
  EXPECT_EQ(c.source, "libcamera");
  EXPECT_EQ(c.board_path, "/usr/share/h4cam/boards/aprilgrid_6x6_30mm.yaml");
  EXPECT_EQ(c.camera_intrinsics_path, "/var/lib/h4cam/camera.yaml");
  EXPECT_EQ(c.camera_id, "");
  EXPECT_EQ(c.MessageCameraId(), "h4cam");
  EXPECT_EQ(c.width_px, 2028);
  EXPECT_EQ(c.height_px, 1520);
  EXPECT_FALSE(c.rotate_180);
  EXPECT_EQ(c.exposure_time_us, 10000);
  EXPECT_EQ(c.analogue_gain, 1.0);
  EXPECT_EQ(c.frame_duration_us, 100000);
  EXPECT_EQ(c.frames_averaged, 10);
  EXPECT_EQ(c.max_spread_px, 0.5);
  EXPECT_EQ(c.lcm_url, "");
  EXPECT_EQ(c.auth_key_file, "") << "authentication is off by default";
}

TEST(ServiceConfigTest, OptionalKeysAreRead) {
  const ServiceConfig c = ParseServiceConfig(
      "source: sim\ncamera:\n  name: bench\nmeasurement:\n  free_run_hz: 2\n"
      "service:\n  heartbeat_period_s: 0.5\nlcm:\n  url: memq://\n"
      "  auth_key_file: /etc/h4cam/h4.key\n",
      "c.yaml");
  EXPECT_EQ(c.source, "sim");
  EXPECT_EQ(c.MessageCameraId(), "bench");
  EXPECT_EQ(c.free_run_hz, 2);
  EXPECT_EQ(c.heartbeat_period_s, 0.5);
  EXPECT_EQ(c.lcm_url, "memq://");
  EXPECT_EQ(c.auth_key_file, "/etc/h4cam/h4.key");
}

void ExpectError(const std::string& text, int line, const std::string& field,
                 const std::string& what) {
  try {
    ParseServiceConfig(text, "svc.yaml");
    FAIL() << "no error for:\n" << text;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.file(), "svc.yaml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(ServiceConfigTest, ErrorsNameTheFileLineAndField) {
  ExpectError("board: b.yaml\nmeasurement:\n  frames_averaged: ten\n", 3,
              "measurement.frames_averaged", "ten");
  ExpectError("measurement:\n  frames_averaged: 0\n", 2, "measurement.frames_averaged", "1..1000");
  ExpectError("camera:\n  id: x\n  rotate_180: maybe\n", 3, "camera.rotate_180", "true or false");
  ExpectError("camera:\n  analogue_gain: 0.5\n", 2, "camera.analogue_gain", ">= 1");
}

// A stream or camera control no camera has: a 100000 x 100000 stream would size every
// frame buffer from it, 1e300 us does not convert to libcamera's integer controls.
TEST(ServiceConfigTest, ImpossibleStreamSizesAndControlsAreRefusedWithTheirLine) {
  ExpectError("camera:\n  width: 100000\n", 2, "camera.width", "32..16384");
  // Issue 42 point 1: libapriltag segfaults on a frame 4 px high.
  ExpectError("camera:\n  height: 4\n", 2, "camera.height", "32..16384");
  ExpectError("camera:\n  width: 8192\n  height: 8192\n", 3, "camera.height", "too large");
  ExpectError("camera:\n  exposure_time_us: 1e300\n", 2, "camera.exposure_time_us", "0..1e+07");
  ExpectError("camera:\n  analogue_gain: 1e300\n", 2, "camera.analogue_gain", "1..64");
  ExpectError("camera:\n  frame_duration_us: 1e-300\n", 2, "camera.frame_duration_us",
              "1000..1e+07");
  ExpectError("measurement:\n  free_run_hz: 1e300\n", 2, "measurement.free_run_hz", "0..100");
  ExpectError("service:\n  heartbeat_period_s: 1e9\n", 2, "service.heartbeat_period_s", "0..3600");
  // The same limits hold after command-line overrides.
  ServiceConfig config;
  std::string why;
  config.exposure_time_us = 1e300;
  EXPECT_FALSE(config.IsValid(&why));
  EXPECT_NE(why.find("exposure time"), std::string::npos) << why;
  config = ServiceConfig{};
  config.width_px = 20000;
  EXPECT_FALSE(config.IsValid(&why));
  EXPECT_NE(why.find("20000x1520"), std::string::npos) << why;
}

TEST(ServiceConfigTest, MisspeltKeyIsRejected) {
  try {
    ParseServiceConfig("camera:\n  exposure_us: 100\n", "svc.yaml");
    FAIL() << "misspelt key accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("exposure_us"), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), 2) << e.what();
  }
}

// A configuration file holding `text` for one test, removed after it.
class ConfigFile {
 public:
  explicit ConfigFile(const std::string& text)
      : path_((std::filesystem::temp_directory_path() /
               ("h4cam_service_config_test_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                ".yaml"))
                  .string()) {
    std::ofstream(path_) << text;
  }
  ~ConfigFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// `h4cam run`'s command line parsed as the program parses it, then resolved.
ServiceConfig ResolveCommandLine(const std::string& line) {
  CLI::App command;
  RunFlags flags;
  DeclareRunOptions(&command, &flags);
  command.parse(line);
  return ResolveRunConfig(flags);
}

TEST(ServiceConfigTest, FlagsOverrideTheFileWhereverConfigStands) {
  const ConfigFile file("source: libcamera\nboard: a.yaml\nmeasurement:\n  frames_averaged: 10\n");
  for (const std::string& line :
       {"--source dir:/tmp/images --frames 4 --config " + file.path() +
            " --camera-id cam7 --auth-key /tmp/h4.key",
        "--config " + file.path() +
            " --source dir:/tmp/images --frames 4 --camera-id cam7 --auth-key /tmp/h4.key"}) {
    const ServiceConfig c = ResolveCommandLine(line);
    EXPECT_EQ(c.source, "dir:/tmp/images") << line;
    EXPECT_EQ(c.board_path, "a.yaml") << line;
    EXPECT_EQ(c.frames_averaged, 4) << line;
    EXPECT_EQ(c.camera_id, "cam7") << line;
    EXPECT_EQ(c.MessageCameraId(), "cam7") << line;
    EXPECT_EQ(c.auth_key_file, "/tmp/h4.key") << line;
  }
  EXPECT_THROW(ResolveCommandLine("--source webcam"), std::invalid_argument);
}

// Only the flags given override: one left out keeps the file's value, and one given with
// the default's value still replaces the file's.
TEST(ServiceConfigTest, FlagsNotGivenKeepTheFileValues) {
  const ConfigFile file(
      "source: sim\nmeasurement:\n  frames_averaged: 5\n  free_run_hz: 2\n"
      "lcm:\n  url: memq://\n");
  const ServiceConfig c = ResolveCommandLine("--frames 10 --config " + file.path());
  EXPECT_EQ(c.frames_averaged, 10);
  EXPECT_EQ(c.source, "sim");
  EXPECT_EQ(c.free_run_hz, 2);
  EXPECT_EQ(c.lcm_url, "memq://");
  EXPECT_EQ(ResolveCommandLine("--free-run 0.5").free_run_hz, 0.5);
  EXPECT_EQ(ResolveCommandLine("").frames_averaged, ServiceConfig{}.frames_averaged);
}

TEST(ServiceConfigTest, FileErrorsStandWhateverTheFlags) {
  const ConfigFile file("camera:\n  exposure_us: 100\n");
  try {
    ResolveCommandLine("--camera-id cam7 --config " + file.path());
    FAIL() << "misspelt key accepted";
  } catch (const FormatError& e) {
    EXPECT_EQ(e.field(), "camera.exposure_us") << e.what();
    EXPECT_EQ(e.line(), 2) << e.what();
  }
  EXPECT_THROW(ResolveCommandLine("--frames 0"), CLI::ValidationError);
}

TEST(ServiceConfigTest, SimRendersTheProcessedPresetUnlessToldOtherwise) {
  const ServiceConfig defaults = ParseServiceConfig("source: sim\n", "c.yaml");
  EXPECT_EQ(defaults.sim_render.response, ResponseCurve::kSrgb);
  EXPECT_EQ(defaults.sim_render.full_well_electrons,
            RenderOptions::Processed().full_well_electrons);

  const ServiceConfig c = ParseServiceConfig(
      "source: sim\nsim:\n  preset: clean\n  blur_sigma_px: 1.4\n  response: gamma:0.7\n"
      "  illumination_gradient: 0.3\n  read_noise: 0.5\n  pixel_blur_sigma_px: 0.6\n",
      "c.yaml");
  EXPECT_EQ(c.sim_render.blur_sigma_px, 1.4);
  EXPECT_EQ(c.sim_render.pixel_blur_sigma_px, 0.6);
  EXPECT_EQ(RenderOptions::Processed().pixel_blur_sigma_px, 0.0);
  EXPECT_EQ(c.sim_render.response, ResponseCurve::kGamma);
  EXPECT_EQ(c.sim_render.response_gamma, 0.7);
  EXPECT_EQ(c.sim_render.illumination_gradient, 0.3);
  EXPECT_EQ(c.sim_render.noise_sigma, 0.5);
  EXPECT_EQ(c.sim_render.full_well_electrons, 0.0);  // the clean preset's

  EXPECT_EQ(ResolveCommandLine("--source sim --sim-preset clean").sim_render.response,
            ResponseCurve::kLinear);
  EXPECT_THROW(ResolveCommandLine("--source sim --sim-preset vivid"), std::invalid_argument);
  // --sim-preset replaces the file's sim: block, the keys it sets over the preset too.
  const ConfigFile file("source: sim\nsim:\n  preset: clean\n  blur_sigma_px: 1.4\n");
  const RenderOptions render =
      ResolveCommandLine("--sim-preset processed --config " + file.path()).sim_render;
  EXPECT_EQ(render.blur_sigma_px, RenderOptions::Processed().blur_sigma_px);
  EXPECT_EQ(render.response, ResponseCurve::kSrgb);
}

TEST(ServiceConfigTest, SimErrorsNameTheLineAndField) {
  ExpectError("sim:\n  preset: vivid\n", 2, "sim.preset", "clean or processed");
  ExpectError("sim:\n  preset: clean\n  blur_sigma_px: 25\n", 3, "sim.blur_sigma_px", "0..20");
  ExpectError("sim:\n  vignetting: 1\n", 2, "sim.vignetting", "0..0.9");
  ExpectError("sim:\n  pixel_blur_sigma_px: -1\n", 2, "sim.pixel_blur_sigma_px", "0..20");
  ExpectError("sim:\n  response: gamma:x\n", 2, "sim.response", "gamma:EXPONENT");
  ExpectError("sim:\n  response: gamma:40\n", 2, "sim.response", "0.1..10");
  ExpectError("sim:\n  full_well_electrons: 50\n", 2, "sim.full_well_electrons", "100..1e7");
  ExpectError("sim:\n  blur: 1\n", 2, "sim.blur", "");
}

}  // namespace
}  // namespace h4::cam
