// The dma-buf read bracket of the libcamera source without a camera: the ioctl sequence
// (start, read, end) on a scripted ioctl, EINTR retried, failures neither fatal nor
// blocking; on a memfd (not a dma-buf: ENOTTY, or ENOSYS under qemu-user) the read goes
// ahead and the failure is logged once; on a real dma-buf
// from udmabuf or a dma-heap, when the kernel offers one, both syncs succeed.
#include "firmware/sources/libcamera_dma_buf_sync.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/dma-buf.h>
#include <linux/dma-heap.h>
#include <linux/udmabuf.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace h4::cam {
namespace {

// A scripted ioctl: answers with `errors` in turn (0 = success, then success forever)
// and records the request and flags of every call.
struct Script {
  std::vector<int> errors;
  size_t next = 0;
  std::vector<unsigned long> requests;
  std::vector<unsigned long long> flags;
};
Script script;

int ScriptedIoctl(int /*fd*/, unsigned long request, void* argument) {
  script.requests.push_back(request);
  script.flags.push_back(static_cast<dma_buf_sync*>(argument)->flags);
  const int error = script.next < script.errors.size() ? script.errors[script.next++] : 0;
  if (error == 0) return 0;
  errno = error;
  return -1;
}

void ResetScript(std::vector<int> errors) { script = Script{std::move(errors), 0, {}, {}}; }

constexpr unsigned long long kStartRead = DMA_BUF_SYNC_START | DMA_BUF_SYNC_READ;
constexpr unsigned long long kEndRead = DMA_BUF_SYNC_END | DMA_BUF_SYNC_READ;

TEST(DmaBufReadSync, BracketsTheReadWithStartAndEnd) {
  ResetScript({});
  {
    const DmaBufReadSync cpu_read(3, &ScriptedIoctl);
    EXPECT_EQ(cpu_read.start_error(), 0);
    ASSERT_EQ(script.flags.size(), 1u);  // started, not yet ended while in scope
    EXPECT_EQ(script.flags[0], kStartRead);
  }
  ASSERT_EQ(script.flags.size(), 2u);
  EXPECT_EQ(script.flags[1], kEndRead);
  for (unsigned long request : script.requests) EXPECT_EQ(request, DMA_BUF_IOCTL_SYNC);
}

TEST(DmaBufReadSync, RetriesAnInterruptedSync) {
  ResetScript({EINTR, EINTR, 0});
  EXPECT_EQ(SyncDmaBuf(3, kStartRead, &ScriptedIoctl), 0);
  EXPECT_EQ(script.requests.size(), 3u);
}

TEST(DmaBufReadSync, AFailedStartIsReportedNotThrownAndSkipsTheEnd) {
  ResetScript({EIO});
  const long failures_before = DmaBufReadSync::FailureCount();
  {
    const DmaBufReadSync cpu_read(3, &ScriptedIoctl);
    EXPECT_EQ(cpu_read.start_error(), EIO);
  }
  EXPECT_EQ(script.requests.size(), 1u);
  EXPECT_EQ(DmaBufReadSync::FailureCount(), failures_before + 1);
}

TEST(DmaBufReadSync, ADriverThatKeepsAnsweringAgainDoesNotBlock) {
  ResetScript(std::vector<int>(1000, EAGAIN));
  EXPECT_EQ(SyncDmaBuf(3, kStartRead, &ScriptedIoctl), EAGAIN);
  EXPECT_LE(script.requests.size(), 16u);
}

// How often `needle` occurs in `text`.
size_t Occurrences(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

// A mapped file that is not a dma-buf: the kernel answers ENOTTY, qemu-user (the
// cross-build's tests, scripts/cross-build) ENOSYS, as it does for an ioctl it does not
// translate. Either way the read goes ahead and the failure is logged once, not per frame.
TEST(DmaBufReadSync, OnAMemfdTheSyncFailsWithEnottyAndTheReadStillWorks) {
  const int fd = memfd_create("h4_dma_buf_sync_test", 0);
  ASSERT_GE(fd, 0) << std::strerror(errno);
  const size_t bytes = 4096;
  ASSERT_EQ(ftruncate(fd, bytes), 0);
  ASSERT_EQ(pwrite(fd, "luma", 4, 0), 4);
  void* address = mmap(nullptr, bytes, PROT_READ, MAP_SHARED, fd, 0);
  ASSERT_NE(address, MAP_FAILED);
  std::ostringstream log;
  const auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
  spdlog::default_logger()->sinks().push_back(sink);
  const bool first_failure_of_the_process = DmaBufReadSync::FailureCount() == 0;
  for (int frame = 0; frame < 3; ++frame) {
    char copy[4] = {};
    {
      const DmaBufReadSync cpu_read(fd);
      EXPECT_TRUE(cpu_read.start_error() == ENOTTY || cpu_read.start_error() == ENOSYS)
          << "errno " << cpu_read.start_error() << ": " << std::strerror(cpu_read.start_error());
      std::memcpy(copy, address, sizeof copy);
    }
    EXPECT_EQ(std::memcmp(copy, "luma", 4), 0) << "frame " << frame;
  }
  spdlog::default_logger()->sinks().pop_back();
  EXPECT_EQ(Occurrences(log.str(), "DMA_BUF_IOCTL_SYNC"), first_failure_of_the_process ? 1u : 0u)
      << log.str();
  munmap(address, bytes);
  close(fd);
}

// A real dma-buf: from the system dma-heap, else udmabuf over a sealed memfd; -1 when the
// kernel offers neither (containers, most CI machines).
int MakeDmaBuf(size_t bytes) {
  if (const int heap = open("/dev/dma_heap/system", O_RDWR | O_CLOEXEC); heap >= 0) {
    dma_heap_allocation_data allocation{};
    allocation.len = bytes;
    allocation.fd_flags = O_RDWR | O_CLOEXEC;
    const int ret = ioctl(heap, DMA_HEAP_IOCTL_ALLOC, &allocation);
    close(heap);
    if (ret == 0) return static_cast<int>(allocation.fd);
  }
  const int device = open("/dev/udmabuf", O_RDWR | O_CLOEXEC);
  if (device < 0) return -1;
  const int memfd = memfd_create("h4_udmabuf", MFD_ALLOW_SEALING);
  int dma_buf = -1;
  if (memfd >= 0 && ftruncate(memfd, static_cast<off_t>(bytes)) == 0 &&
      fcntl(memfd, F_ADD_SEALS, F_SEAL_SHRINK) == 0) {
    udmabuf_create create{};
    create.memfd = static_cast<uint32_t>(memfd);
    create.size = bytes;
    dma_buf = ioctl(device, UDMABUF_CREATE, &create);
  }
  if (memfd >= 0) close(memfd);
  close(device);
  return dma_buf;
}

TEST(DmaBufReadSync, OnARealDmaBufBothSyncsSucceed) {
  const size_t bytes = 4096;
  const int fd = MakeDmaBuf(bytes);
  if (fd < 0) GTEST_SKIP() << "no /dev/dma_heap/system or /dev/udmabuf on this kernel";
  void* address = mmap(nullptr, bytes, PROT_READ, MAP_SHARED, fd, 0);
  ASSERT_NE(address, MAP_FAILED);
  const long failures_before = DmaBufReadSync::FailureCount();
  {
    const DmaBufReadSync cpu_read(fd);
    EXPECT_EQ(cpu_read.start_error(), 0);
    EXPECT_EQ(static_cast<const uint8_t*>(address)[0], 0);
  }
  EXPECT_EQ(DmaBufReadSync::FailureCount(), failures_before);
  munmap(address, bytes);
  close(fd);
}

}  // namespace
}  // namespace h4::cam
