// Configuration of the camera service (`h4cam run --config /etc/h4cam/h4cam.yaml`): the
// YAML file of firmware/packaging/h4cam.yaml, then command-line overrides. Each option is
// a field of ServiceConfig, with its default here: the file's key and the flag
// (firmware/cli/run_command.cpp, DeclareRunOptions) both set that field. Every error
// names the file, the line and the field (h4::FormatError).
#pragma once

#include <string>

#include "firmware/render/render_options.h"

namespace h4::cam {

/// Camera control limits: beyond them a value cannot be meant (and 1e300 us would not
/// convert to libcamera's integer controls). Exposure 0..10 s; gain 1..64 (the sensors
/// libcamera drives stop at 16-64); frame duration 1 ms..10 s (1000..0.1 frames per s).
constexpr double kMaxExposureTime_us = 1e7;
constexpr double kMaxAnalogueGain = 64;
constexpr double kMinFrameDuration_us = 1e3;
constexpr double kMaxFrameDuration_us = 1e7;

struct ServiceConfig {
  /// "libcamera" (default), "sim" (renders H4_SIM_BOARD_TRUTH) or "dir:PATH" (image files
  /// of a folder, in name order). YAML key `source`.
  std::string source = "libcamera";
  std::string board_path;              ///< board YAML (`board`)
  std::string camera_intrinsics_path;  ///< OpenCV camera YAML (`camera_intrinsics`)

  // camera: block
  std::string camera_id;    ///< libcamera id (`camera.id`); "" = the first camera
  std::string camera_name;  ///< id put in messages (`camera.name`); "" = camera_id or "h4cam"
  int width_px = 2028;      ///< stream size, px: within the camera file's limits (camera_yaml.h)
  int height_px = 1520;
  bool rotate_180 = false;
  double exposure_time_us = 10000;    ///< 0 = automatic exposure; at most kMaxExposureTime_us
  double analogue_gain = 1.0;         ///< 1..kMaxAnalogueGain
  double frame_duration_us = 100000;  ///< 10 frames per second; kMin..kMaxFrameDuration_us

  // measurement: block
  int frames_averaged = 10;    ///< default frames per capture request (paper: 10)
  double max_spread_px = 0.5;  ///< motion threshold of the group
  double free_run_hz = 0;      ///< `measurement.free_run_hz`: > 0 measures continuously

  // service: block
  double heartbeat_period_s = 1.0;  ///< camera_status_t period

  // lcm: block
  std::string lcm_url;  ///< "" = $LCM_DEFAULT_URL, else udpm with ttl=0
  /// `lcm.auth_key_file`: the pre-shared key of authenticated messages (messages/README.md);
  /// "" = authentication off (the default).
  std::string auth_key_file;

  // sim: block, the image formation of `source: sim` (render_options.h). `sim.preset`
  // (clean | processed, default processed) sets every value; the other keys override it:
  // blur_sigma_px, focus_distance (m), aperture_diameter (m), illumination_gradient,
  // illumination_gradient_direction_deg, vignetting, full_well_electrons, read_noise
  // (grey levels), response (linear | srgb | gamma:E | table:V0,V1,...).
  RenderOptions sim_render = RenderOptions::Processed();
  /// The camera `--source sim` renders through; empty: camera_intrinsics_path (the file
  /// the measurement assumes is then exact). Command line only (`--sim-camera`).
  std::string sim_camera_path;

  /// The camera name the messages carry.
  std::string MessageCameraId() const;
  /// False with `why` set when a value is out of range (checked after the overrides).
  bool IsValid(std::string* why) const;
};

/// Parses the YAML text; `source_name` names it in errors. Missing keys keep their
/// defaults; unknown keys and wrong types throw h4::FormatError (file:line: field 'x': ...).
ServiceConfig ParseServiceConfig(const std::string& text, const std::string& source_name);
ServiceConfig ReadServiceConfig(const std::string& path);

}  // namespace h4::cam
