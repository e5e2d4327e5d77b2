// The per-sender replay window (messages/bus/replay_guard.h).
#include "messages/bus/replay_guard.h"

#include <gtest/gtest.h>

namespace h4::bus {
namespace {

constexpr int64_t kReplaySecondUs = 1000000;
constexpr int64_t kReplayNowUtime = 1700000000 * kReplaySecondUs;

TEST(ReplayGuardTest, AcceptsEachSequenceOnceInOrder) {
  ReplayGuard guard(8, 90 * kReplaySecondUs);
  for (uint64_t seq = 1; seq <= 200; ++seq)
    EXPECT_TRUE(guard.Accept(7, seq, kReplayNowUtime)) << seq;
  for (uint64_t seq = 1; seq <= 200; ++seq)
    EXPECT_FALSE(guard.Accept(7, seq, kReplayNowUtime)) << seq;
}

TEST(ReplayGuardTest, AcceptsAMessageOvertakenWithinTheWindowOnce) {
  ReplayGuard guard(8, 90 * kReplaySecondUs);
  EXPECT_TRUE(guard.Accept(7, 1, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(7, 3, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(7, 2, kReplayNowUtime)) << "2 arrived after 3";
  EXPECT_FALSE(guard.Accept(7, 2, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(7, 3 + ReplayGuard::kWindow - 1, kReplayNowUtime));
  EXPECT_FALSE(guard.Accept(7, 3, kReplayNowUtime)) << "3 already seen";
  EXPECT_FALSE(guard.Accept(7, 2, kReplayNowUtime)) << "now further back than the window";
}

TEST(ReplayGuardTest, AJumpLargerThanTheWindowForgetsTheBitsBelowIt) {
  ReplayGuard guard(8, 90 * kReplaySecondUs);
  EXPECT_TRUE(guard.Accept(7, 5, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(7, 5 + 1000, kReplayNowUtime));
  EXPECT_FALSE(guard.Accept(7, 5 + 1000, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(7, 5 + 1000 - 1, kReplayNowUtime));
  EXPECT_FALSE(guard.Accept(7, 5, kReplayNowUtime));
}

TEST(ReplayGuardTest, ARestartedSenderWithANewIdStartsAgainFromOne) {
  ReplayGuard guard(8, 90 * kReplaySecondUs);
  for (uint64_t seq = 1; seq <= 10; ++seq) EXPECT_TRUE(guard.Accept(7, seq, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(8, 1, kReplayNowUtime));
  EXPECT_FALSE(guard.Accept(7, 10, kReplayNowUtime));
  EXPECT_EQ(guard.sender_count(), 2u);
}

TEST(ReplayGuardTest, ForgetsSilentSendersAndKeepsAtMostTheLimit) {
  ReplayGuard guard(3, 90 * kReplaySecondUs);
  EXPECT_TRUE(guard.Accept(1, 1, kReplayNowUtime));
  EXPECT_TRUE(guard.Accept(2, 1, kReplayNowUtime + kReplaySecondUs));
  EXPECT_TRUE(guard.Accept(3, 1, kReplayNowUtime + 2 * kReplaySecondUs));
  EXPECT_TRUE(guard.Accept(4, 1, kReplayNowUtime + 3 * kReplaySecondUs));
  EXPECT_EQ(guard.sender_count(), 3u) << "sender 1, the least recently heard, forgotten";
  EXPECT_TRUE(guard.Accept(1, 1, kReplayNowUtime + 3 * kReplaySecondUs))
      << "forgotten, so new again";
  EXPECT_FALSE(guard.Accept(4, 1, kReplayNowUtime + 3 * kReplaySecondUs));
  EXPECT_TRUE(guard.Accept(5, 1, kReplayNowUtime + 200 * kReplaySecondUs));
  EXPECT_EQ(guard.sender_count(), 1u) << "the others silent for more than 90 s";
}

}  // namespace
}  // namespace h4::bus
