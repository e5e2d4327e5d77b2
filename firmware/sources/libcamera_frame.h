// Pure pieces of the libcamera frame source, kept free of libcamera so they are tested
// without a camera: copying the luma (Y) plane out of a mapped buffer honouring its stride,
// and mapping the sensor's monotonic timestamp to utime (microseconds since the epoch).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>
#include <time.h>

namespace h4::cam {

/// Copies the first `height` rows of `width` bytes of an 8-bit luma plane whose rows start
/// every `stride_bytes` bytes into a new CV_8UC1 image (padding bytes dropped). For grey
/// (R8) and for the Y plane of YUV420/NV12 alike. Returns false with `error` set when the
/// sizes are not positive, the stride is shorter than a row, or the plane holds fewer than
/// stride * (height - 1) + width bytes.
bool CopyLumaPlane(const uint8_t* plane, size_t plane_bytes, int width, int height,
                   int stride_bytes, cv::Mat* image, std::string* error);

/// The time on kernel clock `clock` (clock_gettime: CLOCK_REALTIME, CLOCK_MONOTONIC, ...), ns.
int64_t ReadClockNs(clockid_t clock);

/// Which kernel clock a sensor timestamp counts. V4L2 drivers, and so libcamera's
/// SensorTimestamp, use CLOCK_MONOTONIC; some pipelines report CLOCK_BOOTTIME.
enum class SensorClock { kMonotonic, kBoottime };

/// realtime - sensor clock, ns, measured at one instant, and how tightly (half the
/// duration of the best bracketing sample).
struct ClockOffset {
  int64_t realtime_minus_sensor_ns = 0;
  int64_t uncertainty_ns = 0;
};

/// Measures the offset by bracketing a CLOCK_REALTIME read between two reads of the
/// sensor clock, `samples` times, keeping the tightest bracket (the classic way NTP-style
/// tools compare two clocks on one host).
ClockOffset MeasureClockOffset(SensorClock clock, int samples = 8);

/// Sensor timestamp (ns) -> utime (us since the epoch), rounding down.
int64_t SensorNsToUtime(int64_t sensor_ns, const ClockOffset& offset);

}  // namespace h4::cam
