// The pacing rule of the periodic jobs on synthetic times: exactly the rate when polled
// often, one slot (never a burst) after a stall, and the grid kept.
#include "common/timing/periodic_schedule.h"

#include <chrono>
#include <stdexcept>

#include <gtest/gtest.h>

namespace h4 {
namespace {

using std::chrono::milliseconds;
using Clock = PeriodicSchedule::Clock;

TEST(PeriodicSchedule, FirstCallIsDueAndPollingGivesExactlyTheRate) {
  PeriodicSchedule schedule(milliseconds(10));
  EXPECT_FALSE(schedule.next().has_value());
  const Clock::time_point start{};
  int due = 0;
  // 1 s polled every 1 ms at 100 Hz: the slots at 0, 10, ..., 990 ms.
  for (int ms = 0; ms < 1000; ++ms) due += schedule.Due(start + milliseconds(ms)) ? 1 : 0;
  EXPECT_EQ(due, 100);
  EXPECT_EQ(*schedule.next(), start + milliseconds(1000));
}

TEST(PeriodicSchedule, NotDueBeforeTheNextSlotNorTwiceInOne) {
  PeriodicSchedule schedule(milliseconds(10));
  const Clock::time_point start{};
  EXPECT_TRUE(schedule.Due(start));
  EXPECT_FALSE(schedule.Due(start));
  EXPECT_FALSE(schedule.Due(start + milliseconds(9)));
  EXPECT_TRUE(schedule.Due(start + milliseconds(10)));
  EXPECT_FALSE(schedule.Due(start + milliseconds(10)));
}

TEST(PeriodicSchedule, AStallGivesOneSlotAndResumesOnTheGrid) {
  PeriodicSchedule schedule(milliseconds(10));
  const Clock::time_point start{};
  EXPECT_TRUE(schedule.Due(start));
  // 57 ms late: the five missed slots give one, the next is at 60 ms, not 67 ms.
  EXPECT_TRUE(schedule.Due(start + milliseconds(57)));
  EXPECT_EQ(*schedule.next(), start + milliseconds(60));
  EXPECT_FALSE(schedule.Due(start + milliseconds(59)));
  EXPECT_TRUE(schedule.Due(start + milliseconds(60)));
  // A stall of a day is one step too.
  EXPECT_TRUE(schedule.Due(start + std::chrono::hours(24) + milliseconds(3)));
  EXPECT_EQ(*schedule.next(), start + std::chrono::hours(24) + milliseconds(10));
}

TEST(PeriodicSchedule, TimeGoingBackIsNeverDue) {
  PeriodicSchedule schedule(milliseconds(10));
  const Clock::time_point start = Clock::time_point{} + milliseconds(100);
  EXPECT_TRUE(schedule.Due(start));
  EXPECT_FALSE(schedule.Due(start - milliseconds(50)));
  EXPECT_EQ(*schedule.next(), start + milliseconds(10));
}

TEST(PeriodicSchedule, RejectsANonPositivePeriod) {
  EXPECT_THROW(PeriodicSchedule(milliseconds(0)), std::invalid_argument);
  EXPECT_THROW(PeriodicSchedule(milliseconds(-1)), std::invalid_argument);
}

}  // namespace
}  // namespace h4
