// The names of an enum's values, written once as a list that both prints and parses them
// (a result's verdict code, a status in a log line). The list follows the enum's order and
// ends at the value the table names as its last: a list of another length fails to build.
//
//   enum class Fruit { kApple, kPear };
//   constexpr EnumNames<Fruit, Fruit::kPear> kFruitNames = {"apple", "pear"};
//   kFruitNames.NameOf(Fruit::kPear);  // "pear"
//   kFruitNames.ValueNamed("apple");   // Fruit::kApple
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace h4 {

template <typename Enum, Enum kLast>
class EnumNames {
 public:
  /// The enum's values 0 .. kLast.
  static constexpr std::size_t kCount = static_cast<std::size_t>(kLast) + 1;

  template <typename... Names>
  constexpr EnumNames(Names... names) : names_{names...} {  // NOLINT: implicit, for `= {...}`
    static_assert(sizeof...(Names) == kCount, "one name for each value, in the enum's order");
  }

  /// The name of `value`; `unknown` for a value outside the enum (an integer cast to it).
  constexpr const char* NameOf(Enum value, const char* unknown = "?") const {
    const auto index = static_cast<std::size_t>(value);
    return index < kCount ? names_[index] : unknown;
  }

  /// Every name, in the enum's order.
  constexpr const std::array<const char*, kCount>& names() const { return names_; }

  /// The value named `text`; nullopt for any other text.
  constexpr std::optional<Enum> ValueNamed(std::string_view text) const {
    for (std::size_t i = 0; i < kCount; ++i) {
      if (text == names_[i]) return static_cast<Enum>(i);
    }
    return std::nullopt;
  }

 private:
  std::array<const char*, kCount> names_;
};

}  // namespace h4
