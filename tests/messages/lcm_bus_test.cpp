// The bus adapter (messages/bus/lcm_bus.h) against hostile traffic, through real LCM
// dispatch: on memq:// in-process, and on udpm:// between two LCM instances inside a private
// network namespace (scripts/in-private-netns; skipped where none can be made). Before the
// layout check, the first such message threw std::length_error out of Handle() and the next
// Handle() aborted the process inside LCM (lcm.c: `!lcm->in_handle`).
#include "messages/bus/lcm_bus.h"

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "messages/channels.h"
#include "tests/messages/wire_bytes.h"
#include "tests/support/private_netns.h"

namespace h4::bus {
namespace {

using wire_bytes::Encode;
using wire_bytes::PutBigEndian32;
using wire_bytes::SampleBoardPose;

h4msgs::joint_state_t GoodJointState() {
  h4msgs::joint_state_t m{};
  m.utime = 1700000000000000;
  m.joint_count = 4;
  m.position = {0.1, 0.2, 0.3, 0.4};
  return m;
}

/// Hostile messages: string lengths 0 and negative, joint_count -1, and
/// random bytes after a valid fingerprint.
struct HostileSet {
  std::vector<std::vector<uint8_t>> board_poses, joint_states, camera_statuses;
};

HostileSet MakeHostileSet(int random_count) {
  HostileSet set;
  for (int32_t length : {0, -1, INT_MIN, INT_MAX}) {
    std::vector<uint8_t> pose = Encode(SampleBoardPose(1));
    PutBigEndian32(&pose, 8 + 16, length);  // camera_id's length
    set.board_poses.push_back(pose);
    h4msgs::camera_status_t status{};
    status.camera_id = "sim";
    std::vector<uint8_t> bytes = Encode(status);
    PutBigEndian32(&bytes, 8 + 8, length);  // camera_id's length
    set.camera_statuses.push_back(bytes);
  }
  for (int32_t count : {-1, INT_MAX, 1 << 27}) {
    std::vector<uint8_t> joints = Encode(GoodJointState());
    PutBigEndian32(&joints, 8 + 16, count);  // joint_count
    set.joint_states.push_back(joints);
  }
  std::mt19937 rng(13);
  for (int i = 0; i < random_count; ++i) {
    std::vector<uint8_t> bytes(8 + rng() % 600);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    const auto hash = static_cast<uint64_t>(h4msgs::board_pose_t::getHash());
    for (int k = 0; k < 8; ++k) bytes[static_cast<size_t>(k)] = uint8_t(hash >> (56 - 8 * k));
    set.board_poses.push_back(bytes);
  }
  return set;
}

struct Received {
  std::vector<int64_t> board_pose_ids;
  int joint_states = 0;
  int camera_statuses = 0;
};

void SubscribeAll(LcmBus& bus, Received* received) {
  bus.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose, [received](const auto& m) {
    received->board_pose_ids.push_back(m.pose_id);
  });
  bus.Subscribe<h4msgs::joint_state_t>(channels::kJointState,
                                       [received](const auto&) { ++received->joint_states; });
  bus.Subscribe<h4msgs::camera_status_t>(channels::kCameraStatus,
                                         [received](const auto&) { ++received->camera_statuses; });
}

void PublishRaw(lcm::LCM& lcm, const char* channel, const std::vector<uint8_t>& bytes) {
  lcm.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

TEST(LcmBus, HostileMessagesAreCountedPerChannelAndTheLoopGoesOn) {
  LcmBus bus("memq://");
  Received received;
  SubscribeAll(bus, &received);
  const HostileSet hostile = MakeHostileSet(200);
  int64_t sent = 0;
  for (const auto& bytes : hostile.board_poses) {
    PublishRaw(bus.lcm(), channels::kBoardPose, bytes);
    ASSERT_NO_THROW(bus.Handle(std::chrono::milliseconds(0)));
    ++sent;
  }
  for (const auto& bytes : hostile.joint_states)
    PublishRaw(bus.lcm(), channels::kJointState, bytes);
  for (const auto& bytes : hostile.camera_statuses) {
    PublishRaw(bus.lcm(), channels::kCameraStatus, bytes);
  }
  bus.Publish(channels::kBoardPose, SampleBoardPose(7));
  bus.Publish(channels::kJointState, GoodJointState());
  while (bus.Handle(std::chrono::milliseconds(0)) > 0) {
  }

  EXPECT_EQ(received.board_pose_ids, std::vector<int64_t>{7}) << "only the valid one";
  EXPECT_EQ(received.joint_states, 1);
  EXPECT_EQ(received.camera_statuses, 0);
  EXPECT_EQ(bus.decode_failures(channels::kBoardPose), sent);
  EXPECT_EQ(bus.decode_failures(channels::kJointState),
            static_cast<int64_t>(hostile.joint_states.size()));
  EXPECT_EQ(bus.decode_failures(channels::kCameraStatus),
            static_cast<int64_t>(hostile.camera_statuses.size()));
  EXPECT_EQ(bus.decode_failures(), sent + static_cast<int64_t>(hostile.joint_states.size() +
                                                               hostile.camera_statuses.size()));
}

TEST(LcmBus, AHandlersExceptionComesOutOfHandleAndTheBusKeepsWorking) {
  LcmBus bus("memq://");
  int calls = 0;
  bus.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose, [&](const h4msgs::board_pose_t& m) {
    ++calls;
    if (m.pose_id == 1) throw std::runtime_error("disk full");
  });
  bus.Publish(channels::kBoardPose, SampleBoardPose(1));
  try {
    bus.Handle(std::chrono::milliseconds(0));
    FAIL() << "the handler's exception must come out of Handle()";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full");
  }
  // LCM returned normally, so the next handle() does not trip LCM's assertions.
  bus.Publish(channels::kBoardPose, SampleBoardPose(2));
  EXPECT_EQ(bus.Handle(std::chrono::milliseconds(0)), 1);
  EXPECT_EQ(calls, 2);
}

TEST(WarningThrottle, LogsTheFirstThenAtMostOncePerIntervalWithTheCountHeldBack) {
  WarningThrottle throttle(std::chrono::seconds(1));
  const WarningThrottle::Clock::time_point t0{std::chrono::hours(1)};
  int64_t suppressed = -1;
  EXPECT_TRUE(throttle.Allow(t0, &suppressed));
  EXPECT_EQ(suppressed, 0);
  for (int i = 1; i <= 999; ++i) {
    EXPECT_FALSE(throttle.Allow(t0 + std::chrono::microseconds(i * 1000), &suppressed));
  }
  EXPECT_TRUE(throttle.Allow(t0 + std::chrono::seconds(1), &suppressed));
  EXPECT_EQ(suppressed, 999);
}

constexpr const char* kUdpmUrl = "udpm://239.255.76.67:7667?ttl=0";

// Runs inside the namespace (started by the test below through scripts/in-private-netns):
// another LCM instance sends the hostile set over real multicast.
TEST(LcmBusUdpm, ChildInNamespace) {
  if (!test::InPrivateNamespace()) GTEST_SKIP() << "only inside scripts/in-private-netns";
  LcmBus bus(kUdpmUrl);
  ASSERT_TRUE(bus.good()) << bus.error();
  Received received;
  SubscribeAll(bus, &received);
  lcm::LCM sender(kUdpmUrl);
  ASSERT_TRUE(sender.good());
  const HostileSet hostile = MakeHostileSet(500);
  // In small batches: the kernel's receive buffer and LCM's queue are not the subject here.
  size_t next = 0;
  while (next < hostile.board_poses.size()) {
    for (int i = 0; i < 20 && next < hostile.board_poses.size(); ++i) {
      PublishRaw(sender, channels::kBoardPose, hostile.board_poses[next++]);
    }
    for (const auto& bytes : hostile.joint_states) PublishRaw(sender, channels::kJointState, bytes);
    while (bus.Handle(std::chrono::milliseconds(20)) > 0) {
    }
  }
  const h4msgs::board_pose_t valid = SampleBoardPose(9);
  sender.publish(channels::kBoardPose, &valid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (received.board_pose_ids.empty() && std::chrono::steady_clock::now() < deadline) {
    bus.Handle(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(received.board_pose_ids, std::vector<int64_t>{9});
  EXPECT_EQ(received.joint_states, 0);
  // Multicast on loopback may drop under load; most must have arrived and been refused.
  EXPECT_GT(bus.decode_failures(channels::kBoardPose),
            static_cast<int64_t>(hostile.board_poses.size() / 2));
  EXPECT_GT(bus.decode_failures(channels::kJointState), 0);
}

TEST(LcmBusUdpm, SurvivesHostileMulticastInAPrivateNamespace) {
  test::RunChildTestInPrivateNamespace("LcmBusUdpm.ChildInNamespace", 60);
}

}  // namespace
}  // namespace h4::bus
