// The camera service configuration file; see service_config.h.
#include "firmware/service/service_config.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/formats/camera_yaml.h"
#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "common/formats/yaml_map.h"
#include "common/text/invalid_reason.h"
#include "firmware/sources/frame_source_spec.h"

namespace h4::cam {
namespace {

// A scalar string that may be empty (camera.id "" means "the first camera").
std::string OptionalString(const YamlMap& map, const std::string& key,
                           const std::string& fallback) {
  if (!map.Has(key)) return fallback;
  const YAML::Node value = map.Get(key);
  if (value.IsNull()) return "";
  if (!value.IsScalar()) map.Fail(key, "expected a string");
  return value.Scalar();
}

bool OptionalBool(const YamlMap& map, const std::string& key, bool fallback) {
  if (!map.Has(key)) return fallback;
  const YAML::Node value = map.Get(key);
  if (value.IsScalar()) {
    if (value.Scalar() == "true") return true;
    if (value.Scalar() == "false") return false;
  }
  map.Fail(key, "expected true or false");
}

double OptionalDouble(const YamlMap& map, const std::string& key, double fallback) {
  return map.Has(key) ? map.Double(key) : fallback;
}

int OptionalInt(const YamlMap& map, const std::string& key, int fallback) {
  if (!map.Has(key)) return fallback;
  const int64_t value = map.Int(key);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) {
    map.Fail(key, "integer out of range");
  }
  return static_cast<int>(value);
}

// Range checks on the values read, so that the error names the line.
void CheckPositive(const YamlMap& map, const std::string& key, double value) {
  if (map.Has(key) && !(value > 0)) map.Fail(key, "expected a positive number");
}
void CheckRange(const YamlMap& map, const std::string& key, double value, double lo, double hi) {
  if (map.Has(key) && !(value >= lo && value <= hi)) {
    map.Fail(key, fmt::format("expected {:g}..{:g}", lo, hi));
  }
}

// A number of the sim: block within [lo, hi], else an error naming its line.
double SimDouble(const YamlMap& sim, const std::string& key, double fallback, double lo,
                 double hi) {
  const double value = OptionalDouble(sim, key, fallback);
  CheckRange(sim, key, value, lo, hi);
  return value;
}

// The sim: block over the preset it names (processed when it names none). The ranges
// are those of RenderOptions::IsValid.
RenderOptions ParseSimBlock(const YamlMap& sim) {
  sim.RejectUnknownKeys({"preset", "blur_sigma_px", "pixel_blur_sigma_px", "focus_distance",
                         "aperture_diameter", "illumination_gradient",
                         "illumination_gradient_direction_deg", "vignetting", "full_well_electrons",
                         "read_noise", "response"});
  RenderOptions o = RenderOptions::Processed();
  const std::string preset = OptionalString(sim, "preset", "processed");
  if (!RenderPresetByName(preset, &o)) sim.Fail("preset", "expected clean or processed");
  o.blur_sigma_px = SimDouble(sim, "blur_sigma_px", o.blur_sigma_px, 0, 20);
  o.pixel_blur_sigma_px = SimDouble(sim, "pixel_blur_sigma_px", o.pixel_blur_sigma_px, 0, 20);
  o.focus_distance = SimDouble(sim, "focus_distance", o.focus_distance, 0, 1000);
  o.aperture_diameter = SimDouble(sim, "aperture_diameter", o.aperture_diameter, 0, 0.05);
  o.illumination_gradient = SimDouble(sim, "illumination_gradient", o.illumination_gradient, 0, 1);
  o.illumination_gradient_direction_deg = SimDouble(
      sim, "illumination_gradient_direction_deg", o.illumination_gradient_direction_deg, -360, 360);
  o.vignetting = SimDouble(sim, "vignetting", o.vignetting, 0, 0.9);
  o.full_well_electrons = SimDouble(sim, "full_well_electrons", o.full_well_electrons, 0, 1e7);
  if (o.full_well_electrons > 0 && o.full_well_electrons < 100) {
    sim.Fail("full_well_electrons", "expected 0 (no shot noise) or 100..1e7");
  }
  o.noise_sigma = SimDouble(sim, "read_noise", o.noise_sigma, 0, 50);
  std::string why;
  if (sim.Has("response")) {
    if (!ParseResponseCurve(OptionalString(sim, "response", ""), &o, &why) || !o.IsValid(&why)) {
      sim.Fail("response", why);
    }
  }
  return o;
}

}  // namespace

std::string ServiceConfig::MessageCameraId() const {
  if (!camera_name.empty()) return camera_name;
  return camera_id.empty() ? "h4cam" : camera_id;
}

bool ServiceConfig::IsValid(std::string* why) const {
  std::string source_why;
  if (!ParseFrameSourceSpec(source, &source_why)) return Invalid(why, source_why);
  if (frames_averaged < 1 || frames_averaged > 1000) {
    return Invalid(why, fmt::format("frames averaged {}: expected 1..1000", frames_averaged));
  }
  if (!(free_run_hz >= 0) || free_run_hz > 100) {
    return Invalid(why, "free-run rate: expected 0..100 Hz");
  }
  if (!(heartbeat_period_s > 0) || heartbeat_period_s > 3600) {
    return Invalid(why, "heartbeat period: expected (0, 3600] s");
  }
  if (const std::string problem = ImageSizeProblem(width_px, height_px); !problem.empty()) {
    return Invalid(why, "camera stream " + problem);
  }
  if (!(exposure_time_us >= 0 && exposure_time_us <= kMaxExposureTime_us)) {
    return Invalid(why, fmt::format("exposure time {:g} us: expected 0..{:g} us", exposure_time_us,
                                    kMaxExposureTime_us));
  }
  if (!(analogue_gain >= 1 && analogue_gain <= kMaxAnalogueGain)) {
    return Invalid(
        why, fmt::format("analogue gain {:g}: expected 1..{:g}", analogue_gain, kMaxAnalogueGain));
  }
  if (!(frame_duration_us >= kMinFrameDuration_us && frame_duration_us <= kMaxFrameDuration_us)) {
    return Invalid(why, fmt::format("frame duration {:g} us: expected {:g}..{:g} us",
                                    frame_duration_us, kMinFrameDuration_us, kMaxFrameDuration_us));
  }
  if (!(max_spread_px > 0)) {
    return Invalid(why, "measurement max spread: expected a positive px value");
  }
  std::string render_why;
  if (!sim_render.IsValid(&render_why)) return Invalid(why, "sim: " + render_why);
  return true;
}

ServiceConfig ParseServiceConfig(const std::string& text, const std::string& source_name) {
  ServiceConfig config;
  const YAML::Node root = LoadYaml(text, source_name);
  if (!root.IsDefined() || root.IsNull()) return config;  // empty file: every default
  if (!root.IsMap()) throw FormatError(source_name, 1, "", "expected a YAML mapping");
  const YamlMap top(root, source_name, "", 1);
  top.RejectUnknownKeys(
      {"source", "board", "camera_intrinsics", "camera", "measurement", "service", "lcm", "sim"});
  config.source = OptionalString(top, "source", config.source);
  config.board_path = OptionalString(top, "board", "");
  config.camera_intrinsics_path = OptionalString(top, "camera_intrinsics", "");

  if (top.Has("camera")) {
    const YamlMap camera = top.Map("camera");
    camera.RejectUnknownKeys({"id", "name", "width", "height", "rotate_180", "exposure_time_us",
                              "analogue_gain", "frame_duration_us"});
    config.camera_id = OptionalString(camera, "id", "");
    config.camera_name = OptionalString(camera, "name", "");
    config.width_px = OptionalInt(camera, "width", config.width_px);
    CheckRange(camera, "width", config.width_px, kMinImageSide_px, kMaxImageSide_px);
    config.height_px = OptionalInt(camera, "height", config.height_px);
    CheckRange(camera, "height", config.height_px, kMinImageSide_px, kMaxImageSide_px);
    if (int64_t{config.width_px} * config.height_px > kMaxImagePixels) {
      camera.Fail(camera.Has("height") ? "height" : "width",
                  fmt::format("stream {}x{} is too large (at most {} px)", config.width_px,
                              config.height_px, kMaxImagePixels));
    }
    config.rotate_180 = OptionalBool(camera, "rotate_180", config.rotate_180);
    config.exposure_time_us = OptionalDouble(camera, "exposure_time_us", config.exposure_time_us);
    CheckRange(camera, "exposure_time_us", config.exposure_time_us, 0, kMaxExposureTime_us);
    config.analogue_gain = OptionalDouble(camera, "analogue_gain", config.analogue_gain);
    if (camera.Has("analogue_gain") && !(config.analogue_gain >= 1)) {
      camera.Fail("analogue_gain", "expected a gain >= 1");
    }
    CheckRange(camera, "analogue_gain", config.analogue_gain, 1, kMaxAnalogueGain);
    config.frame_duration_us =
        OptionalDouble(camera, "frame_duration_us", config.frame_duration_us);
    CheckRange(camera, "frame_duration_us", config.frame_duration_us, kMinFrameDuration_us,
               kMaxFrameDuration_us);
  }
  if (top.Has("measurement")) {
    const YamlMap m = top.Map("measurement");
    m.RejectUnknownKeys({"frames_averaged", "max_spread_px", "free_run_hz"});
    config.frames_averaged = OptionalInt(m, "frames_averaged", config.frames_averaged);
    if (m.Has("frames_averaged") && (config.frames_averaged < 1 || config.frames_averaged > 1000)) {
      m.Fail("frames_averaged", "expected 1..1000 frames");
    }
    config.max_spread_px = OptionalDouble(m, "max_spread_px", config.max_spread_px);
    CheckPositive(m, "max_spread_px", config.max_spread_px);
    config.free_run_hz = OptionalDouble(m, "free_run_hz", config.free_run_hz);
    CheckRange(m, "free_run_hz", config.free_run_hz, 0, 100);
  }
  if (top.Has("service")) {
    const YamlMap s = top.Map("service");
    s.RejectUnknownKeys({"heartbeat_period_s"});
    config.heartbeat_period_s = OptionalDouble(s, "heartbeat_period_s", config.heartbeat_period_s);
    CheckPositive(s, "heartbeat_period_s", config.heartbeat_period_s);
    CheckRange(s, "heartbeat_period_s", config.heartbeat_period_s, 0, 3600);
  }
  if (top.Has("lcm")) {
    const YamlMap l = top.Map("lcm");
    l.RejectUnknownKeys({"url", "auth_key_file"});
    config.lcm_url = OptionalString(l, "url", "");
    config.auth_key_file = OptionalString(l, "auth_key_file", "");
  }
  if (top.Has("sim")) config.sim_render = ParseSimBlock(top.Map("sim"));
  std::string why;
  if (!config.IsValid(&why)) throw FormatError(source_name, 0, "", why);
  return config;
}

ServiceConfig ReadServiceConfig(const std::string& path) {
  return ParseServiceConfig(ReadTextFile(path), path);
}

}  // namespace h4::cam
