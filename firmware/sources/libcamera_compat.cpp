// libcamera version adapter (see libcamera_compat.h): each function has one branch per API
// generation and nothing else, so porting to a new libcamera touches only this file.
#include "firmware/sources/libcamera_compat.h"

#include <array>

#include <fmt/format.h>
#include <libcamera/control_ids.h>
#include <libcamera/property_ids.h>
#if H4_LIBCAMERA_AT_LEAST(0, 2, 0)
#include <libcamera/orientation.h>
#else
#include <libcamera/transform.h>
#endif

namespace h4::cam::compat {

std::string CompiledLibcameraVersion() {
  return fmt::format("{}.{}.{}", LIBCAMERA_VERSION_MAJOR, LIBCAMERA_VERSION_MINOR,
                     LIBCAMERA_VERSION_PATCH);
}

std::unique_ptr<libcamera::CameraConfiguration> GenerateConfiguration(libcamera::Camera& camera,
                                                                      libcamera::StreamRole role) {
#if H4_LIBCAMERA_AT_LEAST(0, 1, 0)
  // Since 0.1 the roles are a Span<const StreamRole>; StreamRoles (a vector) is gone.
  const std::array<libcamera::StreamRole, 1> roles{role};
  return camera.generateConfiguration(libcamera::Span<const libcamera::StreamRole>(roles));
#else
  const libcamera::StreamRoles roles{role};
  return camera.generateConfiguration(roles);
#endif
}

void SetRotation180(libcamera::CameraConfiguration& config, bool rotate_180) {
#if H4_LIBCAMERA_AT_LEAST(0, 2, 0)
  config.orientation =
      rotate_180 ? libcamera::Orientation::Rotate180 : libcamera::Orientation::Rotate0;
#else
  config.transform = rotate_180 ? libcamera::Transform::Rot180 : libcamera::Transform::Identity;
#endif
}

void SetExposureControls(libcamera::ControlList& controls, bool auto_exposure,
                         int32_t exposure_time_us, float analogue_gain) {
  namespace lc = libcamera::controls;
#if H4_LIBCAMERA_AT_LEAST(0, 5, 0)
  // 0.5 split AeEnable into one mode per quantity (and removed AeEnable).
  controls.set(lc::ExposureTimeMode,
               auto_exposure ? lc::ExposureTimeModeAuto : lc::ExposureTimeModeManual);
  controls.set(lc::AnalogueGainMode,
               auto_exposure ? lc::AnalogueGainModeAuto : lc::AnalogueGainModeManual);
#else
  controls.set(lc::AeEnable, auto_exposure);
#endif
  if (!auto_exposure) {
    controls.set(lc::ExposureTime, exposure_time_us);
    controls.set(lc::AnalogueGain, analogue_gain);
  }
}

void SetFrameDuration(libcamera::ControlList& controls, int64_t frame_duration_us) {
  controls.set(libcamera::controls::FrameDurationLimits,
               libcamera::Span<const int64_t, 2>({frame_duration_us, frame_duration_us}));
}

std::optional<int64_t> SensorTimestampNs(const libcamera::ControlList& metadata) {
  // get() returns std::optional<int64_t> in every version this project supports (>= 0.0.1).
  const auto timestamp = metadata.get(libcamera::controls::SensorTimestamp);
  if (!timestamp) return std::nullopt;
  return static_cast<int64_t>(*timestamp);
}

std::optional<std::string> CameraModel(const libcamera::Camera& camera) {
  const auto model = camera.properties().get(libcamera::properties::Model);
  if (!model) return std::nullopt;
  return std::string(*model);
}

}  // namespace h4::cam::compat
