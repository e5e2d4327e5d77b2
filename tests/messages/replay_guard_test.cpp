// The per-sender replay window (messages/bus/replay_guard.h).
#include "messages/bus/replay_guard.h"

#include <gtest/gtest.h>

namespace h4::bus {
namespace {

constexpr int64_t kSecond = 1000000;
constexpr int64_t kNow = 1700000000 * kSecond;

TEST(ReplayGuardTest, AcceptsEachSequenceOnceInOrder) {
  ReplayGuard guard(8, 90 * kSecond);
  for (uint64_t seq = 1; seq <= 200; ++seq) EXPECT_TRUE(guard.Accept(7, seq, kNow)) << seq;
  for (uint64_t seq = 1; seq <= 200; ++seq) EXPECT_FALSE(guard.Accept(7, seq, kNow)) << seq;
}

TEST(ReplayGuardTest, AcceptsAMessageOvertakenWithinTheWindowOnce) {
  ReplayGuard guard(8, 90 * kSecond);
  EXPECT_TRUE(guard.Accept(7, 1, kNow));
  EXPECT_TRUE(guard.Accept(7, 3, kNow));
  EXPECT_TRUE(guard.Accept(7, 2, kNow)) << "2 arrived after 3";
  EXPECT_FALSE(guard.Accept(7, 2, kNow));
  EXPECT_TRUE(guard.Accept(7, 3 + ReplayGuard::kWindow - 1, kNow));
  EXPECT_FALSE(guard.Accept(7, 3, kNow)) << "3 already seen";
  EXPECT_FALSE(guard.Accept(7, 2, kNow)) << "now further back than the window";
}

TEST(ReplayGuardTest, AJumpLargerThanTheWindowForgetsTheBitsBelowIt) {
  ReplayGuard guard(8, 90 * kSecond);
  EXPECT_TRUE(guard.Accept(7, 5, kNow));
  EXPECT_TRUE(guard.Accept(7, 5 + 1000, kNow));
  EXPECT_FALSE(guard.Accept(7, 5 + 1000, kNow));
  EXPECT_TRUE(guard.Accept(7, 5 + 1000 - 1, kNow));
  EXPECT_FALSE(guard.Accept(7, 5, kNow));
}

TEST(ReplayGuardTest, ARestartedSenderWithANewIdStartsAgainFromOne) {
  ReplayGuard guard(8, 90 * kSecond);
  for (uint64_t seq = 1; seq <= 10; ++seq) EXPECT_TRUE(guard.Accept(7, seq, kNow));
  EXPECT_TRUE(guard.Accept(8, 1, kNow));
  EXPECT_FALSE(guard.Accept(7, 10, kNow));
  EXPECT_EQ(guard.sender_count(), 2u);
}

TEST(ReplayGuardTest, ForgetsSilentSendersAndKeepsAtMostTheLimit) {
  ReplayGuard guard(3, 90 * kSecond);
  EXPECT_TRUE(guard.Accept(1, 1, kNow));
  EXPECT_TRUE(guard.Accept(2, 1, kNow + kSecond));
  EXPECT_TRUE(guard.Accept(3, 1, kNow + 2 * kSecond));
  EXPECT_TRUE(guard.Accept(4, 1, kNow + 3 * kSecond));
  EXPECT_EQ(guard.sender_count(), 3u) << "sender 1, the least recently heard, forgotten";
  EXPECT_TRUE(guard.Accept(1, 1, kNow + 3 * kSecond)) << "forgotten, so new again";
  EXPECT_FALSE(guard.Accept(4, 1, kNow + 3 * kSecond));
  EXPECT_TRUE(guard.Accept(5, 1, kNow + 200 * kSecond));
  EXPECT_EQ(guard.sender_count(), 1u) << "the others silent for more than 90 s";
}

}  // namespace
}  // namespace h4::bus
