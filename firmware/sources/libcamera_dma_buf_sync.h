// CPU access to a libcamera buffer (a dma-buf) bracketed by DMA_BUF_IOCTL_SYNC: the
// kernel flushes or invalidates the CPU caches for the buffer at SYNC_START and SYNC_END,
// so a read between the two sees what the camera's DMA wrote and not stale cache lines
// (rpicam-apps syncs the same way when a request completes and when it is re-queued).
// Free of libcamera: it needs only the buffer's file descriptor, so it is tested without
// a camera.
#pragma once

namespace h4::cam {

/// The ioctl the guard calls; a seam so that tests can script EINTR and failures.
using DmaBufIoctl = int (*)(int fd, unsigned long request, void* argument);

/// DMA_BUF_IOCTL_SYNC with `flags` (DMA_BUF_SYNC_* from linux/dma-buf.h) on `fd`, retried
/// while it fails with EINTR or EAGAIN (at most 16 attempts). Returns 0, or the errno of
/// the last failure.
int SyncDmaBuf(int fd, unsigned long long flags, DmaBufIoctl ioctl_call);

/// RAII bracket of a CPU read of a dma-buf: SYNC_START | SYNC_READ on construction,
/// SYNC_END | SYNC_READ on destruction (only when the start succeeded). A failed sync is not fatal
/// (the read goes ahead: on a cache-coherent system, or a buffer that is not a dma-buf, it is still
/// right); the first failure in the process is logged with its errno, later ones only counted.
class DmaBufReadSync {
 public:
  explicit DmaBufReadSync(int fd, DmaBufIoctl ioctl_call = nullptr);
  ~DmaBufReadSync();
  DmaBufReadSync(const DmaBufReadSync&) = delete;
  DmaBufReadSync& operator=(const DmaBufReadSync&) = delete;

  /// errno of the SYNC_START ioctl, 0 when it succeeded.
  int start_error() const { return start_error_; }

  /// Failed sync ioctls (start or end) in this process so far.
  static long FailureCount();

 private:
  int fd_;
  DmaBufIoctl ioctl_call_;
  int start_error_ = 0;
};

}  // namespace h4::cam
