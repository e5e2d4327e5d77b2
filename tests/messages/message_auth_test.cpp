// The authenticated-message trailer (messages/bus/message_auth.h): what a key holder seals
// opens once, and every alteration, other key, other channel, replay or stale copy is refused
// with its reason.
#include "messages/bus/message_auth.h"

#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/options_check.h"

namespace h4::bus {
namespace {

constexpr int64_t kAuthSecondUs = 1000000;
constexpr int64_t kAuthNowUtime = 1700000000 * kAuthSecondUs;
const std::string kChannel = "H4_BOARD_POSE";

AuthKey FilledKey(uint8_t fill) { return AuthKey{std::vector<uint8_t>(32, fill), "test key"}; }

std::vector<uint8_t> Message() { return {'a', 'n', ' ', 'l', 'c', 'm', ' ', 'm', 's', 'g'}; }

struct Opened {
  AuthVerdict verdict;
  size_t size;
};

Opened Open(MessageAuthenticator& receiver, const std::vector<uint8_t>& sealed,
            const std::string& channel = kChannel, int64_t now = kAuthNowUtime) {
  size_t size = 0;
  const AuthVerdict verdict = receiver.Open(channel, sealed.data(), sealed.size(), now, &size);
  return {verdict, size};
}

/// Message() as `sender` seals it on kChannel at `utime`.
std::vector<uint8_t> Sealed(MessageAuthenticator& sender, int64_t utime = kAuthNowUtime) {
  const std::vector<uint8_t> message = Message();
  return sender.Seal(kChannel, message.data(), message.size(), utime);
}

TEST(MessageAuthTest, ASealedMessageOpensToItsBytesAndTheTrailerHasItsSize) {
  MessageAuthenticator sender(FilledKey(1), {});
  MessageAuthenticator receiver(FilledKey(1), {});
  const std::vector<uint8_t> message = Message();
  const std::vector<uint8_t> sealed = Sealed(sender);
  ASSERT_EQ(sealed.size(), message.size() + kAuthTrailerBytes);
  EXPECT_TRUE(std::equal(message.begin(), message.end(), sealed.begin()));
  const Opened opened = Open(receiver, sealed);
  EXPECT_EQ(opened.verdict, AuthVerdict::kAccepted);
  EXPECT_EQ(opened.size, message.size());
}

TEST(MessageAuthTest, EveryAlteredByteIsRefused) {
  MessageAuthenticator sender(FilledKey(1), {});
  const std::vector<uint8_t> message = Message();
  const std::vector<uint8_t> sealed = Sealed(sender);
  for (size_t i = 0; i < sealed.size(); ++i) {
    MessageAuthenticator receiver(FilledKey(1), {});
    std::vector<uint8_t> altered = sealed;
    altered[i] ^= 0x20;
    const AuthVerdict verdict = Open(receiver, altered).verdict;
    EXPECT_NE(verdict, AuthVerdict::kAccepted) << "byte " << i;
    const size_t trailer_at = message.size();
    if (i < trailer_at || i >= trailer_at + 12) {
      EXPECT_EQ(verdict, AuthVerdict::kForged) << "byte " << i;
    }
  }
}

TEST(MessageAuthTest, AnotherKeyIsAForeignKeyAndAForgedKeyIdIsForged) {
  MessageAuthenticator sender(FilledKey(1), {});
  MessageAuthenticator receiver(FilledKey(2), {});
  const std::vector<uint8_t> message = Message();
  std::vector<uint8_t> sealed = Sealed(sender);
  EXPECT_EQ(Open(receiver, sealed).verdict, AuthVerdict::kForeignKey);
  // The attacker copies the receiver's key id from one of its genuine messages.
  MessageAuthenticator genuine(FilledKey(2), {});
  const std::vector<uint8_t> real = Sealed(genuine);
  std::copy_n(real.begin() + static_cast<long>(message.size()) + 4, 8,
              sealed.begin() + static_cast<long>(message.size()) + 4);
  EXPECT_EQ(Open(receiver, sealed).verdict, AuthVerdict::kForged);
}

TEST(MessageAuthTest, AMessageReplayedOntoAnotherChannelIsRefused) {
  MessageAuthenticator sender(FilledKey(1), {});
  MessageAuthenticator receiver(FilledKey(1), {});
  const std::vector<uint8_t> sealed = Sealed(sender);
  EXPECT_EQ(Open(receiver, sealed, "H4_CAPTURE_REQUEST").verdict, AuthVerdict::kForged);
  EXPECT_EQ(Open(receiver, sealed, kChannel).verdict, AuthVerdict::kAccepted);
}

TEST(MessageAuthTest, AReplayedMessageIsRefusedAndAnOvertakenOneAcceptedOnce) {
  MessageAuthenticator sender(FilledKey(1), {});
  MessageAuthenticator receiver(FilledKey(1), {});
  const auto first = Sealed(sender);
  const auto second = Sealed(sender);
  EXPECT_EQ(Open(receiver, second).verdict, AuthVerdict::kAccepted);
  EXPECT_EQ(Open(receiver, first).verdict, AuthVerdict::kAccepted) << "overtaken, within window";
  EXPECT_EQ(Open(receiver, first).verdict, AuthVerdict::kReplayed);
  EXPECT_EQ(Open(receiver, second).verdict, AuthVerdict::kReplayed);
}

TEST(MessageAuthTest, ARestartedSenderIsAcceptedAndItsOldMessagesStayRefused) {
  MessageAuthenticator receiver(FilledKey(1), {});
  std::vector<std::vector<uint8_t>> before;
  {
    MessageAuthenticator sender(FilledKey(1), {});
    for (int i = 0; i < 5; ++i) {
      before.push_back(Sealed(sender));
      EXPECT_EQ(Open(receiver, before.back()).verdict, AuthVerdict::kAccepted);
    }
  }
  MessageAuthenticator restarted(FilledKey(1), {});  // a new process: a new sender id, sequence 1
  const auto after = Sealed(restarted, kAuthNowUtime + kAuthSecondUs);
  EXPECT_EQ(Open(receiver, after, kChannel, kAuthNowUtime + kAuthSecondUs).verdict,
            AuthVerdict::kAccepted);
  for (const auto& old : before) {
    EXPECT_EQ(Open(receiver, old, kChannel, kAuthNowUtime + kAuthSecondUs).verdict,
              AuthVerdict::kReplayed);
  }
}

TEST(MessageAuthTest, ARecordedMessageIsStaleOutsideTheClockWindowEvenForANewReceiver) {
  AuthOptions options;
  options.max_clock_offset_s = 30;
  MessageAuthenticator sender(FilledKey(1), options);
  const auto sealed = Sealed(sender);
  MessageAuthenticator later(FilledKey(1), options);
  EXPECT_EQ(Open(later, sealed, kChannel, kAuthNowUtime + 31 * kAuthSecondUs).verdict,
            AuthVerdict::kStale);
  EXPECT_EQ(Open(later, sealed, kChannel, kAuthNowUtime - 31 * kAuthSecondUs).verdict,
            AuthVerdict::kStale);
  EXPECT_EQ(Open(later, sealed, kChannel, kAuthNowUtime + 29 * kAuthSecondUs).verdict,
            AuthVerdict::kAccepted);
  options.check_freshness = false;  // reading a recorded log
  MessageAuthenticator log_reader(FilledKey(1), options);
  EXPECT_EQ(Open(log_reader, sealed, kChannel, kAuthNowUtime + 3600 * kAuthSecondUs).verdict,
            AuthVerdict::kAccepted);
  EXPECT_EQ(Open(log_reader, sealed, kChannel, kAuthNowUtime + 3600 * kAuthSecondUs).verdict,
            AuthVerdict::kReplayed);
}

TEST(MessageAuthTest, AnUnsignedOrTruncatedMessageIsUnauthenticated) {
  MessageAuthenticator receiver(FilledKey(1), {});
  EXPECT_EQ(Open(receiver, Message()).verdict, AuthVerdict::kUnauthenticated);
  EXPECT_EQ(Open(receiver, {}).verdict, AuthVerdict::kUnauthenticated);
  EXPECT_EQ(Open(receiver, std::vector<uint8_t>(kAuthTrailerBytes + 5, 0)).verdict,
            AuthVerdict::kUnauthenticated);
  MessageAuthenticator sender(FilledKey(1), {});
  auto sealed = Sealed(sender);
  sealed.pop_back();
  EXPECT_NE(Open(receiver, sealed).verdict, AuthVerdict::kAccepted);
}

TEST(MessageAuthTest, RandomTrailersWithTheRightMagicAndKeyIdAreNeverAccepted) {
  MessageAuthenticator sender(FilledKey(1), {});
  MessageAuthenticator receiver(FilledKey(1), {});
  const std::vector<uint8_t> genuine = Sealed(sender);
  std::mt19937 rng(13);
  for (int i = 0; i < 5000; ++i) {
    std::vector<uint8_t> bytes(kAuthTrailerBytes + rng() % 200);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    // Magic and key id copied from a genuine trailer: only the MAC stands in the way.
    std::copy_n(genuine.end() - static_cast<long>(kAuthTrailerBytes), 12,
                bytes.end() - static_cast<long>(kAuthTrailerBytes));
    EXPECT_EQ(Open(receiver, bytes).verdict, AuthVerdict::kForged) << i;
  }
}

TEST(MessageAuthTest, RefusesAShortKeyAndInvalidOptions) {
  EXPECT_THROW(MessageAuthenticator(AuthKey{std::vector<uint8_t>(31, 1), "k"}, {}),
               std::invalid_argument);
  AuthOptions options;
  options.max_clock_offset_s = 0;
  EXPECT_TRUE(RefusedNaming(options, "max_clock_offset_s"));
  EXPECT_THROW(MessageAuthenticator(FilledKey(1), options), std::invalid_argument);
  options = {};
  options.channels.clear();
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(MessageAuthTest, CoversOnlyItsChannels) {
  MessageAuthenticator auth(FilledKey(1), {});
  EXPECT_TRUE(auth.Covers("H4_BOARD_POSE"));
  EXPECT_TRUE(auth.Covers("H4_CAPTURE_REQUEST"));
  EXPECT_TRUE(auth.Covers("H4_CAMERA_STATUS"));
  EXPECT_FALSE(auth.Covers("H4_JOINT_STATE"));
  EXPECT_FALSE(auth.Covers("H4_ROBOT_TARGET"));
}

}  // namespace
}  // namespace h4::bus
