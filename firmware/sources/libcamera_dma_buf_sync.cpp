// dma-buf CPU access bracketing; see libcamera_dma_buf_sync.h.
#include "firmware/sources/libcamera_dma_buf_sync.h"

#include <atomic>
#include <cerrno>
#include <cstring>

#include <linux/dma-buf.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>

namespace h4::cam {
namespace {

std::atomic<long> failures{0};

// EINTR (a signal during the kernel's wait for the device's fences) is retried; a bound
// keeps a driver that keeps answering EAGAIN from stalling the frame loop.
constexpr int kMaxSyncAttempts = 16;

int SystemIoctl(int fd, unsigned long request, void* argument) {
  return ::ioctl(fd, request, argument);
}

// At 30 frames per second a persistent failure would flood the log: say it once.
void RecordFailure(int fd, const char* phase, int error) {
  if (failures.fetch_add(1) == 0) {
    spdlog::warn(
        "dma-buf: DMA_BUF_IOCTL_SYNC {} on fd {} failed: {} (the frame is read anyway; "
        "further failures are not logged)",
        phase, fd, std::strerror(error));
  }
}

}  // namespace

int SyncDmaBuf(int fd, unsigned long long flags, DmaBufIoctl ioctl_call) {
  dma_buf_sync sync{};
  sync.flags = flags;
  int error = 0;
  for (int attempt = 0; attempt < kMaxSyncAttempts; ++attempt) {
    if (ioctl_call(fd, DMA_BUF_IOCTL_SYNC, &sync) == 0) return 0;
    error = errno;
    if (error != EINTR && error != EAGAIN) return error;
  }
  return error;
}

DmaBufReadSync::DmaBufReadSync(int fd, DmaBufIoctl ioctl_call)
    : fd_(fd), ioctl_call_(ioctl_call != nullptr ? ioctl_call : &SystemIoctl) {
  start_error_ = SyncDmaBuf(fd_, DMA_BUF_SYNC_START | DMA_BUF_SYNC_READ, ioctl_call_);
  if (start_error_ != 0) RecordFailure(fd_, "start", start_error_);
}

DmaBufReadSync::~DmaBufReadSync() {
  if (start_error_ != 0) return;  // nothing was started: the end would fail the same way
  const int error = SyncDmaBuf(fd_, DMA_BUF_SYNC_END | DMA_BUF_SYNC_READ, ioctl_call_);
  if (error != 0) RecordFailure(fd_, "end", error);
}

long DmaBufReadSync::FailureCount() { return failures.load(); }

}  // namespace h4::cam
