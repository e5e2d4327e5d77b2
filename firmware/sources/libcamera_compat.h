// The one place that knows which libcamera it is built against. Debian bookworm ships
// libcamera 0.0.3; Raspberry Pi OS ships a newer fork (0.1 .. 0.5+). Every API difference
// the frame source meets is wrapped here, selected by LIBCAMERA_VERSION_MAJOR/MINOR/PATCH
// from <libcamera/version.h>, so libcamera_source.cpp compiles unchanged against both:
//   - generateConfiguration: std::vector<StreamRole> (0.0.x) vs Span<const StreamRole> (>= 0.1)
//   - image rotation: CameraConfiguration::transform (< 0.2) vs ::orientation (>= 0.2)
//   - manual exposure: AeEnable = false (< 0.5) vs ExposureTimeMode/AnalogueGainMode = Manual
//     (>= 0.5, where AeEnable was removed upstream)
//   - metadata lookup: ControlList::get returns std::optional<T> (>= 0.0.1) and the type of
//     SensorTimestamp (int64_t ns in every released version, read through one function).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <libcamera/camera.h>
#include <libcamera/controls.h>
#include <libcamera/stream.h>
#include <libcamera/version.h>

/// True when the libcamera being compiled against is at least major.minor.patch.
#define H4_LIBCAMERA_AT_LEAST(major, minor, patch)                              \
  ((LIBCAMERA_VERSION_MAJOR > (major)) ||                                       \
   (LIBCAMERA_VERSION_MAJOR == (major) && LIBCAMERA_VERSION_MINOR > (minor)) || \
   (LIBCAMERA_VERSION_MAJOR == (major) && LIBCAMERA_VERSION_MINOR == (minor) && \
    LIBCAMERA_VERSION_PATCH >= (patch)))

namespace h4::cam::compat {

/// "0.0.3": the version the code was compiled against (the headers').
std::string CompiledLibcameraVersion();

/// One-stream configuration for `role` (nullptr when the camera does not support it).
std::unique_ptr<libcamera::CameraConfiguration> GenerateConfiguration(libcamera::Camera& camera,
                                                                      libcamera::StreamRole role);

/// Requests the image rotated by 180 degrees (a camera mounted upside down) or not rotated.
void SetRotation180(libcamera::CameraConfiguration& config, bool rotate_180);

/// Fixed exposure for measurement: auto exposure off, the given exposure time (us) and
/// analogue gain. `auto_exposure` true restores the camera's automatic control instead.
void SetExposureControls(libcamera::ControlList& controls, bool auto_exposure,
                         int32_t exposure_time_us, float analogue_gain);

/// Frame duration limits (min = max = `frame_duration_us`) fixing the frame rate.
void SetFrameDuration(libcamera::ControlList& controls, int64_t frame_duration_us);

/// controls::SensorTimestamp of a completed request (ns, the kernel's monotonic clock for
/// V4L2 devices), nullopt when the pipeline did not report it.
std::optional<int64_t> SensorTimestampNs(const libcamera::ControlList& metadata);

/// controls::Model property of a camera, nullopt when absent.
std::optional<std::string> CameraModel(const libcamera::Camera& camera);

}  // namespace h4::cam::compat
