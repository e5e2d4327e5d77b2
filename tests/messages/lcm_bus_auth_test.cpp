// The bus adapter with authentication on (messages/bus/lcm_bus.h, BusAuth) through real LCM
// dispatch on memq://: messages of the authenticated channels reach their handlers only when
// signed with the bus's key, fresh and new; the others are counted by reason and dropped.
#include <vector>

#include <gtest/gtest.h>

#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"
#include "tests/messages/wire_bytes.h"

namespace h4::bus {
namespace {

using wire_bytes::Encode;

AuthKey BusTestKey(uint8_t fill) { return AuthKey{std::vector<uint8_t>(32, fill), "test key"}; }

int64_t WallUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

h4msgs::board_pose_t TestBoardPose(int64_t pose_id) {
  return wire_bytes::SampleBoardPose(pose_id, WallUtime());
}

void PublishBytes(LcmBus& bus, const char* channel, const std::vector<uint8_t>& bytes) {
  bus.lcm().publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

void DrainQueue(LcmBus& bus) {
  while (bus.Handle(std::chrono::milliseconds(0)) > 0) {
  }
}

/// A bus with authentication on that records the board pose ids and joint states it hears.
struct AuthenticatedBus {
  LcmBus bus{"memq://", WireLimits{}, BusAuth{BusTestKey(1), AuthOptions{}}};
  std::vector<int64_t> pose_ids;
  int joint_states = 0;

  AuthenticatedBus() {
    bus.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose,
                                        [this](const auto& m) { pose_ids.push_back(m.pose_id); });
    bus.Subscribe<h4msgs::joint_state_t>(channels::kJointState,
                                         [this](const auto&) { ++joint_states; });
  }
};

TEST(LcmBusAuth, ItsOwnSignedMessagesPassAndUnsignedOnesAreCountedAndDropped) {
  AuthenticatedBus node;
  node.bus.Publish(channels::kBoardPose, TestBoardPose(1));
  PublishBytes(node.bus, channels::kBoardPose, Encode(TestBoardPose(66)));  // no trailer
  DrainQueue(node.bus);
  EXPECT_EQ(node.pose_ids, std::vector<int64_t>{1});
  EXPECT_EQ(node.bus.auth_failures(channels::kBoardPose), 1);
  EXPECT_EQ(node.bus.auth_failures(AuthVerdict::kUnauthenticated), 1);
  EXPECT_EQ(node.bus.decode_failures(), 0);
}

TEST(LcmBusAuth, AnotherKeyHoldersMessageIsAcceptedOnceAndItsReplayDropped) {
  AuthenticatedBus node;
  MessageAuthenticator camera(BusTestKey(1), {});  // another process holding the key
  const std::vector<uint8_t> message = Encode(TestBoardPose(2));
  const std::vector<uint8_t> sealed =
      camera.Seal(channels::kBoardPose, message.data(), message.size(), WallUtime());
  PublishBytes(node.bus, channels::kBoardPose, sealed);
  PublishBytes(node.bus, channels::kBoardPose, sealed);
  PublishBytes(node.bus, channels::kCaptureRequest, sealed);  // onto another channel
  DrainQueue(node.bus);
  EXPECT_EQ(node.pose_ids, std::vector<int64_t>{2});
  EXPECT_EQ(node.bus.auth_failures(AuthVerdict::kReplayed), 1);
}

TEST(LcmBusAuth, ForeignKeyAndTamperedMessagesAreDroppedWithTheirReason) {
  AuthenticatedBus node;
  MessageAuthenticator attacker(BusTestKey(9), {});
  const std::vector<uint8_t> message = Encode(TestBoardPose(3));
  PublishBytes(node.bus, channels::kBoardPose,
               attacker.Seal(channels::kBoardPose, message.data(), message.size(), WallUtime()));
  MessageAuthenticator camera(BusTestKey(1), {});
  std::vector<uint8_t> tampered =
      camera.Seal(channels::kBoardPose, message.data(), message.size(), WallUtime());
  tampered[20] ^= 0x01;  // inside pose_id
  PublishBytes(node.bus, channels::kBoardPose, tampered);
  DrainQueue(node.bus);
  EXPECT_TRUE(node.pose_ids.empty());
  EXPECT_EQ(node.bus.auth_failures(AuthVerdict::kForeignKey), 1);
  EXPECT_EQ(node.bus.auth_failures(AuthVerdict::kForged), 1);
  EXPECT_EQ(node.bus.auth_failures(), 2);
}

TEST(LcmBusAuth, ChannelsOutsideTheAuthenticatedSetPassUnsigned) {
  AuthenticatedBus node;
  h4msgs::joint_state_t js{};
  js.utime = WallUtime();
  js.joint_count = 4;
  js.position = {0.1, 0.2, 0.3, 0.4};
  PublishBytes(node.bus, channels::kJointState, Encode(js));  // a third-party controller
  DrainQueue(node.bus);
  EXPECT_EQ(node.joint_states, 1);
  EXPECT_FALSE(node.bus.authenticates(channels::kJointState));
  EXPECT_TRUE(node.bus.authenticates(channels::kBoardPose));
}

TEST(LcmBusAuth, ABusWithoutAuthenticationReadsSignedMessagesUnchecked) {
  LcmBus plain("memq://");
  int received = 0;
  plain.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose, [&](const auto&) { ++received; });
  MessageAuthenticator camera(BusTestKey(1), {});
  const std::vector<uint8_t> message = Encode(TestBoardPose(4));
  PublishBytes(plain, channels::kBoardPose,
               camera.Seal(channels::kBoardPose, message.data(), message.size(), WallUtime()));
  DrainQueue(plain);
  EXPECT_EQ(received, 1) << "the trailer is set aside, as a log replayed without the key";
  EXPECT_EQ(plain.decode_failures(channels::kBoardPose), 0);
  // Only a trailer's length is set aside: a message one byte too long is still refused.
  std::vector<uint8_t> longer = Encode(TestBoardPose(5));
  longer.push_back(0);
  PublishBytes(plain, channels::kBoardPose,
               camera.Seal(channels::kBoardPose, longer.data(), longer.size(), WallUtime()));
  DrainQueue(plain);
  EXPECT_EQ(received, 1);
  EXPECT_EQ(plain.decode_failures(channels::kBoardPose), 1);
}

}  // namespace
}  // namespace h4::bus
