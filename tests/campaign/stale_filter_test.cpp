// host/campaign/stale_filter.h on synthetic times: a publisher's stream is never stale
// whatever its clock's offset, a replayed message an hour old is, a clock set back is
// believed again once its old stamps have left the memory.
#include "host/campaign/stale_filter.h"

#include <gtest/gtest.h>

namespace h4::host {
namespace {

constexpr int64_t kSecond = 1'000'000;
constexpr int64_t kStart = 1'700'000'000 * kSecond;

TEST(StaleMessageFilter, AStreamWithAnyClockOffsetIsNeverStale) {
  for (const int64_t offset : {int64_t{0}, -20 * kSecond, 3600 * kSecond}) {
    StaleMessageFilter filter;
    for (int k = 0; k < 1000; ++k) {
      const int64_t arrival = kStart + k * 10'000;
      // Delivery delays of 0-50 ms, as on a loaded host.
      const int64_t delay = (k * 7919) % 50'000;
      EXPECT_FALSE(filter.Stale(arrival - delay + offset, arrival)) << offset << " " << k;
    }
  }
}

TEST(StaleMessageFilter, MessagesAnHourOldAmongTheLiveOnesAreStale) {
  StaleMessageFilter filter;
  int stale = 0;
  for (int k = 0; k < 300; ++k) {
    const int64_t arrival = kStart + k * 10'000;
    EXPECT_FALSE(filter.Stale(arrival, arrival));
    // Two replayed messages per live one, as the flood sent them.
    stale += filter.Stale(arrival - 3600 * kSecond, arrival + 1);
    stale += filter.Stale(arrival - 3600 * kSecond, arrival + 2);
  }
  EXPECT_EQ(stale, 600);
  // 2.5 s late is stale, 1.5 s is not (max_lag 2 s).
  const int64_t now = kStart + 300 * 10'000;
  EXPECT_TRUE(filter.Stale(now - 2'500'000, now));
  EXPECT_FALSE(filter.Stale(now - 1'500'000, now));
}

TEST(StaleMessageFilter, AClockSetBackIsBelievedOnceItsOldStampsAreForgotten) {
  StaleMessageFilter filter(2.0, 5.0);
  for (int k = 0; k < 100; ++k) filter.Stale(kStart + k * 10'000, kStart + k * 10'000);
  const int64_t jump = kStart + 100 * 10'000;
  // The clock now reads an hour earlier: stale until the last old stamp is 5 s behind.
  EXPECT_TRUE(filter.Stale(jump - 3600 * kSecond, jump));
  EXPECT_TRUE(filter.Stale(jump + 4 * kSecond - 3600 * kSecond, jump + 4 * kSecond));
  EXPECT_FALSE(filter.Stale(jump + 6 * kSecond - 3600 * kSecond, jump + 6 * kSecond));
  EXPECT_FALSE(filter.Stale(jump + 7 * kSecond - 3600 * kSecond, jump + 7 * kSecond));
}

}  // namespace
}  // namespace h4::host
