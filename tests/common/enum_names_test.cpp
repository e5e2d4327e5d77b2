// One list per enum that prints and parses its values (common/text/enum_names.h).
#include "common/text/enum_names.h"

#include <string>

#include <gtest/gtest.h>

namespace h4 {
namespace {

enum class Fruit { kApple, kPear, kFig };
constexpr EnumNames<Fruit, Fruit::kFig> kFruitNames = {"apple", "pear", "fig"};

// The size comes from the last value: a list of another length does not compile.
static_assert(kFruitNames.kCount == 3);

TEST(EnumNames, NamesEachValueInTheEnumsOrder) {
  EXPECT_EQ(std::string(kFruitNames.NameOf(Fruit::kApple)), "apple");
  EXPECT_EQ(std::string(kFruitNames.NameOf(Fruit::kPear)), "pear");
  EXPECT_EQ(std::string(kFruitNames.NameOf(Fruit::kFig)), "fig");
}

TEST(EnumNames, AValueOutsideTheEnumGetsTheUnknownName) {
  EXPECT_EQ(std::string(kFruitNames.NameOf(static_cast<Fruit>(3))), "?");
  EXPECT_EQ(std::string(kFruitNames.NameOf(static_cast<Fruit>(-1), "no fruit")), "no fruit");
}

TEST(EnumNames, ParsesEveryNameBackAndNothingElse) {
  for (Fruit fruit : {Fruit::kApple, Fruit::kPear, Fruit::kFig}) {
    EXPECT_EQ(kFruitNames.ValueNamed(kFruitNames.NameOf(fruit)), fruit);
  }
  EXPECT_FALSE(kFruitNames.ValueNamed("Apple"));
  EXPECT_FALSE(kFruitNames.ValueNamed(""));
  EXPECT_FALSE(kFruitNames.ValueNamed("?"));
}

}  // namespace
}  // namespace h4
