// Strict number parsing and shortest round-trip formatting.
#include "common/formats/number_text.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace h4 {
namespace {

TEST(ParseDouble, AcceptsDecimalForms) {
  double v = 0.0;
  ASSERT_TRUE(ParseDouble("1.5", &v));
  EXPECT_EQ(v, 1.5);
  ASSERT_TRUE(ParseDouble("-2e-3", &v));
  EXPECT_EQ(v, -2e-3);
  ASSERT_TRUE(ParseDouble("+4", &v));
  EXPECT_EQ(v, 4.0);
  ASSERT_TRUE(ParseDouble(".25", &v));
  EXPECT_EQ(v, 0.25);
  ASSERT_TRUE(ParseDouble("0.", &v));  // OpenCV writes zeros this way
  EXPECT_EQ(v, 0.0);
  ASSERT_TRUE(ParseDouble("6.5e+02", &v));
  EXPECT_EQ(v, 650.0);
}

TEST(ParseDouble, RejectsAnythingButAWholeFiniteNumber) {
  double v = 7.0;
  for (const char* bad : {"", " ", "1.0abc", "abc", "nan", "NaN", "inf", "-inf", "infinity", "1e",
                          "--1", "+-1", "++1", "+", "-", "1,5", "0x10", "1e999", " 1"}) {
    EXPECT_FALSE(ParseDouble(bad, &v)) << "'" << bad << "'";
  }
  EXPECT_EQ(v, 7.0);  // untouched
}

TEST(ParseInt64, AcceptsIntegersOnly) {
  int64_t v = 0;
  ASSERT_TRUE(ParseInt64("1700000000000000", &v));
  EXPECT_EQ(v, 1700000000000000);
  ASSERT_TRUE(ParseInt64("-3", &v));
  EXPECT_EQ(v, -3);
  for (const char* bad : {"", "1.0", "1e3", "12a", "99999999999999999999", "nan"}) {
    EXPECT_FALSE(ParseInt64(bad, &v)) << "'" << bad << "'";
  }
}

TEST(FormatDouble, ReadsBackExactlyAndRejectsNonFinite) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  for (int i = 0; i < 1000; ++i) {
    const double x = uniform(rng) * std::pow(10.0, static_cast<double>(i % 40 - 20));
    double back = 0.0;
    ASSERT_TRUE(ParseDouble(FormatDouble(x, "x"), &back));
    EXPECT_EQ(back, x);
  }
  EXPECT_EQ(FormatDouble(0.1, "x"), "0.1");
  EXPECT_THROW(FormatDouble(std::nan(""), "x"), std::invalid_argument);
  EXPECT_THROW(FormatDouble(std::numeric_limits<double>::infinity(), "x"), std::invalid_argument);
}

}  // namespace
}  // namespace h4
