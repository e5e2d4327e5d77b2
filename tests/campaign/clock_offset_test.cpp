// The clock offset of a publisher (host/campaign/clock_offset.h) on synthetic times: the
// least delayed of the recent messages gives the offset, and only agreeing samples count.
#include "host/campaign/clock_offset.h"

#include <gtest/gtest.h>

namespace h4::host {
namespace {

constexpr int64_t kNow = 1'800'000'000'000'000;  // us since the epoch

TEST(ClockOffset, TheLeastDelayedOfAFewAgreeingSamplesIsTheOffset) {
  ClockOffset camera;
  EXPECT_FALSE(camera.seconds());
  // A camera 40 s ahead; its heartbeats arrive 1 to 30 ms after they were stamped.
  camera.Add(kNow + 40'000'000, kNow + 30'000);
  camera.Add(kNow + 41'000'000, kNow + 1'001'000);
  EXPECT_FALSE(camera.seconds()) << "two samples are not yet a consistent offset";
  camera.Add(kNow + 42'000'000, kNow + 2'010'000);
  ASSERT_TRUE(camera.seconds());
  EXPECT_NEAR(*camera.seconds(), 39.999, 1e-9);
  EXPECT_EQ(DescribeClockOffset("camera status timestamps", *camera.seconds()),
            "camera status timestamps are 40.0 s ahead of this host's clock");
  EXPECT_EQ(DescribeClockOffset("joint states", -2.5),
            "joint states are 2.5 s behind this host's clock");
}

TEST(ClockOffset, SamplesThatDisagreeOrAreNoTimesGiveNoOffset) {
  ClockOffset offset(4);
  offset.Add(kNow, kNow);
  offset.Add(kNow, kNow);
  offset.Add(kNow + 3'600'000'000, kNow);  // one foreign message an hour ahead
  EXPECT_FALSE(offset.seconds());
  offset.Add(-5, kNow);  // not a time: ignored
  offset.Add(kNow, 0);
  EXPECT_FALSE(offset.seconds());
  // Once the odd sample has left the window of 4, the offset is the agreeing samples'.
  for (int k = 0; k < 4; ++k) offset.Add(kNow + 1000, kNow);
  ASSERT_TRUE(offset.seconds());
  EXPECT_NEAR(*offset.seconds(), 0.001, 1e-12);
}

}  // namespace
}  // namespace h4::host
