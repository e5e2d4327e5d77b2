// Luma copy and timestamp mapping of the libcamera frame source (see libcamera_frame.h).
#include "firmware/sources/libcamera_frame.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <fmt/format.h>
#include <time.h>

namespace h4::cam {

int64_t ReadClockNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

namespace {

// Floor division: a timestamp before the epoch must not round towards zero.
int64_t FloorDiv(int64_t a, int64_t b) {
  const int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

}  // namespace

bool CopyLumaPlane(const uint8_t* plane, size_t plane_bytes, int width, int height,
                   int stride_bytes, cv::Mat* image, std::string* error) {
  if (plane == nullptr || width <= 0 || height <= 0) {
    *error = fmt::format("luma plane: expected a mapped plane and a positive size, got {}x{}",
                         width, height);
    return false;
  }
  if (stride_bytes < width) {
    *error = fmt::format("luma plane: stride {} bytes is shorter than a row of {} pixels",
                         stride_bytes, width);
    return false;
  }
  const size_t needed = static_cast<size_t>(stride_bytes) * static_cast<size_t>(height - 1) +
                        static_cast<size_t>(width);
  if (plane_bytes < needed) {
    *error = fmt::format("luma plane: {} bytes, expected at least {} for {}x{} with stride {}",
                         plane_bytes, needed, width, height, stride_bytes);
    return false;
  }
  cv::Mat out(height, width, CV_8UC1);
  for (int row = 0; row < height; ++row) {
    std::memcpy(out.ptr<uint8_t>(row), plane + static_cast<size_t>(row) * stride_bytes,
                static_cast<size_t>(width));
  }
  *image = std::move(out);
  return true;
}

ClockOffset MeasureClockOffset(SensorClock clock, int samples) {
  const clockid_t sensor_clock = clock == SensorClock::kBoottime ? CLOCK_BOOTTIME : CLOCK_MONOTONIC;
  ClockOffset best;
  int64_t best_bracket = std::numeric_limits<int64_t>::max();
  for (int i = 0; i < std::max(samples, 1); ++i) {
    const int64_t before = ReadClockNs(sensor_clock);
    const int64_t realtime = ReadClockNs(CLOCK_REALTIME);
    const int64_t after = ReadClockNs(sensor_clock);
    const int64_t bracket = after - before;
    if (bracket < best_bracket) {
      best_bracket = bracket;
      best.realtime_minus_sensor_ns = realtime - (before + bracket / 2);
      best.uncertainty_ns = (bracket + 1) / 2;
    }
  }
  return best;
}

int64_t SensorNsToUtime(int64_t sensor_ns, const ClockOffset& offset) {
  return FloorDiv(sensor_ns + offset.realtime_minus_sensor_ns, 1000);
}

}  // namespace h4::cam
