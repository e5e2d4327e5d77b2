// libcamera frame source (see libcamera_source.h). Every libcamera call whose signature
// differs between versions goes through libcamera_compat.h.
#include "firmware/sources/libcamera_source.h"

#include <algorithm>

#include <fmt/format.h>
#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>
#include <libcamera/control_ids.h>
#include <libcamera/controls.h>
#include <libcamera/formats.h>
#include <libcamera/framebuffer.h>
#include <libcamera/framebuffer_allocator.h>
#include <libcamera/request.h>
#include <libcamera/stream.h>
#include <spdlog/spdlog.h>
#include <sys/mman.h>

#include "common/text/enum_names.h"
#include "firmware/sources/libcamera_compat.h"
#include "firmware/sources/libcamera_dma_buf_sync.h"
#include "firmware/sources/libcamera_manager.h"

namespace h4::cam {
namespace {

using Clock = std::chrono::steady_clock;

// The clock offset drifts as NTP slews CLOCK_REALTIME; re-measuring it this often keeps
// the utime error well below a frame period.
constexpr auto kClockOffsetRefresh = std::chrono::seconds(10);

// Formats whose first plane is 8-bit luma, one byte per pixel.
bool HasLumaFirstPlane(const libcamera::PixelFormat& format) {
  namespace f = libcamera::formats;
  for (const auto& luma :
       {f::R8, f::YUV420, f::YVU420, f::NV12, f::NV21, f::YUV422, f::NV16, f::NV61}) {
    if (format == luma) return true;
  }
  return false;
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

}  // namespace

constexpr EnumNames<LibcameraSource::State, LibcameraSource::State::kRunning>
    kLibcameraSourceStateNames = {"closed", "open", "configured", "running"};

const char* ToString(LibcameraSource::State state) {
  return kLibcameraSourceStateNames.NameOf(state);
}

bool LibcameraSourceOptions::IsValid(std::string* why) const {
  if (width <= 0 || height <= 0) {
    *why = fmt::format("image size must be positive, got {}x{}", width, height);
  } else if (!auto_exposure && exposure_time.count() <= 0) {
    *why = fmt::format("exposure time must be positive, got {} us", exposure_time.count());
  } else if (!auto_exposure && !(analogue_gain >= 1.0f)) {
    *why = fmt::format("analogue gain must be >= 1, got {:f}", analogue_gain);
  } else if (!(frame_rate_hz >= 0.0)) {
    *why = fmt::format("frame rate must be >= 0 (0: camera default), got {:f}", frame_rate_hz);
  } else if (buffer_count < 1) {
    *why = fmt::format("buffer count must be >= 1, got {}", buffer_count);
  } else if (device_timeout.count() <= 0) {
    *why = "device timeout must be positive";
  } else if (max_restarts < 0) {
    *why = "max restarts must be >= 0";
  } else if (pixel_format != "YUV420" && pixel_format != "R8" && pixel_format != "NV12") {
    *why = "pixel format must be YUV420, NV12 or R8, got '" + pixel_format + "'";
  } else {
    return true;
  }
  return false;
}

LibcameraSource::LibcameraSource(LibcameraSourceOptions options) : options_(std::move(options)) {}

LibcameraSource::~LibcameraSource() { Close(); }

std::string LibcameraSource::Describe() const {
  return "libcamera " + (options_.camera_id.empty()
                             ? (camera_ ? camera_->id() : std::string("(first camera)"))
                             : options_.camera_id);
}

bool LibcameraSource::Expect(State expected, const char* call) {
  if (state_ == expected) return true;
  error_ = std::string(call) + "() called while the camera is " + ToString(state_) + "; expected " +
           ToString(expected) + " (lifecycle: Open, Configure, Start, Next..., " + "Stop, Close)";
  return false;
}

bool LibcameraSource::Open() {
  if (!Expect(State::kClosed, "Open")) return false;
  std::string why;
  if (!options_.IsValid(&why)) {
    error_ = "libcamera options: " + why;
    return false;
  }
  manager_ = SharedCameraManager(&error_);
  if (!manager_) return false;

  const auto cameras = manager_->cameras();
  std::vector<std::string> ids;
  for (const auto& camera : cameras) ids.push_back(camera->id());
  const std::string available = ids.empty() ? "no cameras found" : "available: " + Join(ids);
  if (options_.camera_id.empty()) {
    if (!cameras.empty()) camera_ = cameras.front();
  } else {
    camera_ = manager_->get(options_.camera_id);
  }
  if (!camera_) {
    error_ = options_.camera_id.empty()
                 ? "libcamera: no cameras found (is a camera connected and enabled?)"
                 : "libcamera: no camera with id '" + options_.camera_id + "' (" + available + ")";
    manager_.reset();
    return false;
  }
  if (const int ret = camera_->acquire(); ret != 0) {
    error_ =
        fmt::format("libcamera: cannot acquire camera '{}' (in use by another process? error {})",
                    camera_->id(), -ret);
    camera_.reset();
    manager_.reset();
    return false;
  }
  camera_->requestCompleted.connect(this, &LibcameraSource::OnRequestCompleted);
  state_ = State::kOpen;
  spdlog::info("libcamera: acquired camera '{}'", camera_->id());
  return true;
}

bool LibcameraSource::Configure() {
  if (!Expect(State::kOpen, "Configure")) return false;
  const std::string id = camera_->id();
  config_ = compat::GenerateConfiguration(*camera_, libcamera::StreamRole::Viewfinder);
  if (!config_ || config_->size() != 1) {
    error_ = "libcamera: camera '" + id + "' offers no viewfinder stream";
    return false;
  }
  libcamera::StreamConfiguration& stream_config = config_->at(0);
  stream_config.pixelFormat = libcamera::PixelFormat::fromString(options_.pixel_format);
  stream_config.size = libcamera::Size(static_cast<unsigned>(options_.width),
                                       static_cast<unsigned>(options_.height));
  stream_config.bufferCount = static_cast<unsigned>(options_.buffer_count);
  compat::SetRotation180(*config_, options_.rotate_180);

  const auto status = config_->validate();
  if (status == libcamera::CameraConfiguration::Invalid) {
    error_ = fmt::format("libcamera: camera '{}' rejects {} {}x{}", id, options_.pixel_format,
                         options_.width, options_.height);
    return false;
  }
  if (status == libcamera::CameraConfiguration::Adjusted) {
    spdlog::warn("libcamera: camera '{}' adjusted the stream to {}", id, stream_config.toString());
  }
  if (!HasLumaFirstPlane(stream_config.pixelFormat)) {
    error_ = "libcamera: camera '" + id + "' offers " + stream_config.pixelFormat.toString() +
             ", expected a format with an 8-bit luma plane (R8, YUV420, NV12)";
    return false;
  }
  if (const int ret = camera_->configure(config_.get()); ret != 0) {
    error_ = fmt::format("libcamera: configuring camera '{}' failed (error {})", id, -ret);
    return false;
  }
  stream_ = stream_config.stream();
  width_ = static_cast<int>(stream_config.size.width);
  height_ = static_cast<int>(stream_config.size.height);
  stride_ = static_cast<int>(stream_config.stride);

  allocator_ = std::make_unique<libcamera::FrameBufferAllocator>(camera_);
  if (allocator_->allocate(stream_) < 0) {
    error_ = "libcamera: cannot allocate buffers for camera '" + id + "'";
    TeardownStream();
    return false;
  }
  if (!MapBuffers()) {
    TeardownStream();
    return false;
  }
  for (const auto& buffer : allocator_->buffers(stream_)) {
    auto request = camera_->createRequest();
    if (!request || request->addBuffer(stream_, buffer.get()) != 0) {
      error_ = "libcamera: cannot create a request for camera '" + id + "'";
      TeardownStream();
      return false;
    }
    requests_.push_back(std::move(request));
  }

  start_controls_ = std::make_unique<libcamera::ControlList>(libcamera::controls::controls);
  compat::SetExposureControls(*start_controls_, options_.auto_exposure,
                              static_cast<int32_t>(options_.exposure_time.count()),
                              options_.analogue_gain);
  if (options_.frame_rate_hz > 0.0) {
    compat::SetFrameDuration(*start_controls_,
                             static_cast<int64_t>(1e6 / options_.frame_rate_hz + 0.5));
  }
  state_ = State::kConfigured;
  spdlog::info("libcamera: camera '{}' configured: {} stride {}", id, stream_config.toString(),
               stride_);
  return true;
}

bool LibcameraSource::MapBuffers() {
  for (const auto& buffer : allocator_->buffers(stream_)) {
    const auto& plane = buffer->planes().front();
    const size_t offset =
        plane.offset == libcamera::FrameBuffer::Plane::kInvalidOffset ? 0 : plane.offset;
    // mmap offsets must be page aligned: map from the start of the dmabuf.
    const size_t bytes = offset + plane.length;
    void* address = mmap(nullptr, bytes, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
    if (address == MAP_FAILED) {
      error_ = "libcamera: cannot mmap a buffer of camera '" + camera_->id() + "'";
      return false;
    }
    mappings_.push_back({address, bytes});
    luma_planes_[buffer.get()] = {static_cast<const uint8_t*>(address) + offset, plane.length,
                                  plane.fd.get()};
  }
  return true;
}

void LibcameraSource::UnmapBuffers() {
  for (const auto& mapping : mappings_) munmap(mapping.address, mapping.bytes);
  mappings_.clear();
  luma_planes_.clear();
}

void LibcameraSource::TeardownStream() {
  requests_.clear();
  UnmapBuffers();
  if (allocator_ && stream_) allocator_->free(stream_);
  allocator_.reset();
  start_controls_.reset();
  config_.reset();
  stream_ = nullptr;
}

bool LibcameraSource::QueueAllRequests() {
  for (auto& request : requests_) {
    request->reuse(libcamera::Request::ReuseBuffers);
    if (const int ret = camera_->queueRequest(request.get()); ret != 0) {
      error_ = fmt::format("libcamera: cannot queue a request on camera '{}' (error {})",
                           camera_->id(), -ret);
      return false;
    }
  }
  return true;
}

bool LibcameraSource::Start() {
  if (!Expect(State::kConfigured, "Start")) return false;
  clock_offset_ = MeasureClockOffset(options_.sensor_clock);
  last_offset_update_ = Clock::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    completed_.clear();
    accepting_ = true;
  }
  if (const int ret = camera_->start(start_controls_.get()); ret != 0) {
    error_ = fmt::format("libcamera: cannot start camera '{}' (error {})", camera_->id(), -ret);
    std::lock_guard<std::mutex> lock(mutex_);
    accepting_ = false;
    return false;
  }
  state_ = State::kRunning;
  if (!QueueAllRequests()) {
    Stop();
    return false;
  }
  last_frame_time_ = Clock::now();
  return true;
}

void LibcameraSource::OnRequestCompleted(libcamera::Request* request) {
  // Runs on libcamera's thread: hand the request over and return, nothing else.
  if (request->status() == libcamera::Request::RequestCancelled) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!accepting_) return;
    completed_.push_back(request);
  }
  completed_cv_.notify_one();
}

std::optional<Frame> LibcameraSource::Consume(libcamera::Request* request) {
  std::optional<Frame> frame;
  const libcamera::FrameBuffer* buffer = request->findBuffer(stream_);
  if (buffer == nullptr) {
    spdlog::warn("libcamera: completed request without a buffer for the stream");
  } else if (buffer->metadata().status != libcamera::FrameMetadata::FrameSuccess) {
    spdlog::warn("libcamera: camera '{}' dropped frame {} (buffer error)", camera_->id(),
                 buffer->metadata().sequence);
  } else {
    const MappedPlane& plane = luma_planes_.at(buffer);
    Frame out;
    std::string copy_error;
    bool copied = false;
    {  // The CPU reads what the camera's DMA wrote: sync the caches around the copy.
      const DmaBufReadSync cpu_read(plane.dma_buf_fd);
      copied =
          CopyLumaPlane(plane.data, plane.bytes, width_, height_, stride_, &out.image, &copy_error);
    }
    if (!copied) {
      spdlog::warn("libcamera: camera '{}': {}", camera_->id(), copy_error);
    } else {
      if (Clock::now() - last_offset_update_ > kClockOffsetRefresh) {
        clock_offset_ = MeasureClockOffset(options_.sensor_clock);
        last_offset_update_ = Clock::now();
      }
      const int64_t sensor_ns = compat::SensorTimestampNs(request->metadata())
                                    .value_or(static_cast<int64_t>(buffer->metadata().timestamp));
      out.utime = SensorNsToUtime(sensor_ns, clock_offset_);
      out.sequence = static_cast<int64_t>(buffer->metadata().sequence);
      frame = std::move(out);
    }
  }
  // The frame is copied out: the buffer goes straight back to the camera.
  request->reuse(libcamera::Request::ReuseBuffers);
  if (const int ret = camera_->queueRequest(request); ret != 0) {
    spdlog::warn("libcamera: cannot re-queue a request on camera '{}' (error {})", camera_->id(),
                 -ret);
  }
  return frame;
}

std::optional<Frame> LibcameraSource::Next(std::chrono::milliseconds timeout) {
  if (!Expect(State::kRunning, "Next")) return std::nullopt;
  const auto deadline = Clock::now() + timeout;
  while (true) {
    const auto device_deadline = last_frame_time_ + options_.device_timeout;
    libcamera::Request* request = nullptr;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      completed_cv_.wait_until(lock, std::min(deadline, device_deadline),
                               [this] { return !completed_.empty(); });
      if (!completed_.empty()) {
        request = completed_.front();
        completed_.pop_front();
      }
    }
    if (request != nullptr) {
      if (auto frame = Consume(request)) {
        last_frame_time_ = Clock::now();
        restarts_since_frame_ = 0;
        return frame;
      }
      continue;  // a failed frame: keep waiting for a good one
    }
    const auto now = Clock::now();
    if (now >= device_deadline) {
      if (restarts_since_frame_ >= options_.max_restarts) {
        error_ = fmt::format(
            "libcamera: camera '{}' delivered no frame for {} ms after {} restarts; giving up",
            camera_->id(), options_.device_timeout.count(), restarts_since_frame_);
        return std::nullopt;
      }
      if (!Restart()) return std::nullopt;
      continue;
    }
    if (now >= deadline) {
      error_ = fmt::format("libcamera: no frame within {} ms (timeout)", timeout.count());
      return std::nullopt;
    }
  }
}

bool LibcameraSource::Restart() {
  ++restarts_since_frame_;
  ++restarts_total_;
  const std::string id = camera_->id();
  spdlog::warn("libcamera: camera '{}' sent no frame for {} ms; restarting (attempt {}/{})", id,
               options_.device_timeout.count(), restarts_since_frame_, options_.max_restarts);
  Stop();
  if (Start()) return true;
  spdlog::warn("libcamera: restarting camera '{}' failed ({}); reopening it", id, error_);
  // A full reopen re-enumerates the cameras (the device may have been reset).
  Close();
  return Open() && Configure() && Start();
}

void LibcameraSource::Stop() {
  if (state_ != State::kRunning) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    accepting_ = false;
  }
  camera_->stop();  // completes every pending request as cancelled
  {
    std::lock_guard<std::mutex> lock(mutex_);
    completed_.clear();
  }
  state_ = State::kConfigured;
}

void LibcameraSource::Close() {
  Stop();
  TeardownStream();
  if (camera_) {
    camera_->requestCompleted.disconnect(this, &LibcameraSource::OnRequestCompleted);
    if (state_ != State::kClosed) camera_->release();
    camera_.reset();
  }
  manager_.reset();
  state_ = State::kClosed;
}

}  // namespace h4::cam
