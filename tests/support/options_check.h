// Test helper for option structs: IsValid(std::string*) must refuse bad values with a
// reason that names the field, so a user knows what to change.
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace h4 {

/// Success when `options.IsValid` refuses them with a reason containing `field`.
template <typename Options>
::testing::AssertionResult RefusedNaming(const Options& options, const std::string& field) {
  std::string why;
  if (options.IsValid(&why)) return ::testing::AssertionFailure() << "accepted";
  if (why.find(field) == std::string::npos) {
    return ::testing::AssertionFailure() << "the reason does not name '" << field << "': " << why;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace h4
