// The real camera: a FrameSource over libcamera, modelled on rpicam-apps'
// core/rpicam_app.cpp. Explicit lifecycle Open (acquire) -> Configure -> Start -> Next...
// -> Stop -> Close (release); one 8-bit luma stream (grey or YUV420, the Y plane is used);
// fixed exposure and gain for measurement; sensor timestamps mapped to utime. The libcamera
// completion callback only queues the request; Next() copies the frame out and re-queues
// it. When no frame arrives within the device timeout, Next() restarts the camera
// (stop/start, then close/reopen) instead of hanging.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "firmware/frames/frame_source.h"
#include "firmware/sources/libcamera_frame.h"

namespace libcamera {
class Camera;
class CameraConfiguration;
class CameraManager;
class ControlList;
class FrameBuffer;
class FrameBufferAllocator;
class Request;
class Stream;
}  // namespace libcamera

namespace h4::cam {

struct LibcameraSourceOptions {
  /// libcamera camera id (as `h4cam list-cameras` prints it); empty: the first camera.
  std::string camera_id;
  int width = 1024;  ///< px; the paper's set-up (libcamera may adjust it: see Configure)
  int height = 768;  ///< px
  /// Pixel format asked for: "YUV420" (any camera with an ISP) or "R8" (grey sensors).
  /// Whatever libcamera settles on must carry 8-bit luma in its first plane.
  std::string pixel_format = "YUV420";
  bool auto_exposure = false;  ///< measurement wants a fixed exposure: leave false
  std::chrono::microseconds exposure_time{10'000};  ///< fixed exposure time
  float analogue_gain = 1.0f;                       ///< fixed analogue gain (>= 1)
  double frame_rate_hz = 0.0;  ///< fixed frame rate; 0 keeps the camera's default
  bool rotate_180 = false;     ///< camera mounted upside down
  int buffer_count = 4;        ///< buffers (and requests) in flight
  /// No frame for this long while running -> restart the camera.
  std::chrono::milliseconds device_timeout{2'000};
  int max_restarts = 3;  ///< consecutive restarts without a frame before giving up
  SensorClock sensor_clock = SensorClock::kMonotonic;  ///< clock of SensorTimestamp

  /// False with `why` set when an option is out of range.
  bool IsValid(std::string* why) const;
};

class LibcameraSource final : public FrameSource {
 public:
  /// Named by ToString, in this order (libcamera_source.cpp).
  enum class State { kClosed, kOpen, kConfigured, kRunning };

  explicit LibcameraSource(LibcameraSourceOptions options);
  ~LibcameraSource() override;
  LibcameraSource(const LibcameraSource&) = delete;
  LibcameraSource& operator=(const LibcameraSource&) = delete;

  /// Starts the camera manager, selects the camera by id (or the first) and acquires it.
  bool Open() override;
  /// Configures the luma stream, allocates and maps the buffers, creates the requests.
  bool Configure() override;
  /// Starts streaming with the measurement controls and queues every request.
  bool Start() override;
  std::optional<Frame> Next(std::chrono::milliseconds timeout) override;
  void Stop() override;
  /// Frees the buffers and releases the camera (from any state).
  void Close() override;
  std::string Describe() const override;

  State state() const { return state_; }
  int restarts() const { return restarts_total_; }
  /// Size and stride libcamera settled on (valid once configured).
  int width() const { return width_; }
  int height() const { return height_; }
  int stride() const { return stride_; }

 private:
  struct MappedPlane {
    const uint8_t* data = nullptr;
    size_t bytes = 0;
    int dma_buf_fd = -1;  ///< the plane's dma-buf, synced around every CPU read
  };
  struct Mapping {
    void* address = nullptr;
    size_t bytes = 0;
  };

  bool Expect(State expected, const char* call);
  void OnRequestCompleted(libcamera::Request* request);
  bool MapBuffers();
  void UnmapBuffers();
  void TeardownStream();
  bool QueueAllRequests();
  /// Frame from a completed request (nullopt on a failed frame), then re-queues it.
  std::optional<Frame> Consume(libcamera::Request* request);
  bool Restart();

  LibcameraSourceOptions options_;
  State state_ = State::kClosed;
  std::shared_ptr<libcamera::CameraManager> manager_;
  std::shared_ptr<libcamera::Camera> camera_;
  std::unique_ptr<libcamera::CameraConfiguration> config_;
  std::unique_ptr<libcamera::FrameBufferAllocator> allocator_;
  std::unique_ptr<libcamera::ControlList> start_controls_;
  libcamera::Stream* stream_ = nullptr;
  std::vector<std::unique_ptr<libcamera::Request>> requests_;
  std::map<const libcamera::FrameBuffer*, MappedPlane> luma_planes_;
  std::vector<Mapping> mappings_;
  int width_ = 0, height_ = 0, stride_ = 0;

  // Filled by the libcamera thread (OnRequestCompleted), drained by Next().
  std::mutex mutex_;
  std::condition_variable completed_cv_;
  std::deque<libcamera::Request*> completed_;
  bool accepting_ = false;  ///< false while stopping: cancelled requests are dropped

  ClockOffset clock_offset_;
  std::chrono::steady_clock::time_point last_offset_update_;
  std::chrono::steady_clock::time_point last_frame_time_;
  int64_t sequence_ = 0;
  int restarts_since_frame_ = 0;
  int restarts_total_ = 0;
};

const char* ToString(LibcameraSource::State state);

}  // namespace h4::cam
