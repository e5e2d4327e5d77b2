// One interface for every source of camera frames: libcamera (the real camera), image
// files, and the synthetic renderer. The measuring pipeline only sees Frames.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace h4::cam {

/// One 8-bit grey frame. `image` is CV_8UC1 and owns its pixels (a source copies the
/// Y plane out of its buffer, honouring the stride, before handing the frame over).
struct Frame {
  cv::Mat image;
  int64_t utime = 0;     ///< sensor timestamp mapped to microseconds since the epoch
  int64_t sequence = 0;  ///< frame counter of the source
  std::string origin;    ///< file name for file sources, empty otherwise
};

/// Explicit lifecycle (rpicam-apps): Open, Configure, Start, Next..., Stop, Close.
/// Every method returns false with error() set instead of throwing, so the camera
/// service can report the failure on its status channel and restart.
class FrameSource {
 public:
  virtual ~FrameSource() = default;

  virtual bool Open() = 0;
  /// Fixes the image size and the measurement controls (exposure, gain).
  virtual bool Configure() = 0;
  virtual bool Start() = 0;
  /// Waits up to `timeout` for the next frame; nullopt on timeout, end of input or error
  /// (then error() says which; an exhausted file source sets finished()).
  virtual std::optional<Frame> Next(std::chrono::milliseconds timeout) = 0;
  virtual void Stop() = 0;
  virtual void Close() = 0;

  /// Human-readable description ("libcamera <id>", "files: dir/", "sim").
  virtual std::string Describe() const = 0;
  virtual bool finished() const { return false; }
  const std::string& error() const { return error_; }

 protected:
  std::string error_;
};

/// A source with no device behind it (image files, the renderer): nothing to configure,
/// start, stop or close.
class DevicelessFrameSource : public FrameSource {
 public:
  bool Configure() override { return true; }
  bool Start() override { return true; }
  void Stop() override {}
  void Close() override {}
};

}  // namespace h4::cam
