// Test helper for checks on program output and generated text: whether a text contains a
// part, with the whole text in the message either way, so that a failing EXPECT_TRUE or
// EXPECT_FALSE shows what was written.
#pragma once

#include <string>

#include <gtest/gtest.h>

namespace h4 {

/// Success when `text` contains `part`.
inline ::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) == std::string::npos) {
    return ::testing::AssertionFailure() << "no \"" << part << "\" in:\n" << text;
  }
  return ::testing::AssertionSuccess() << "\"" << part << "\" found in:\n" << text;
}

}  // namespace h4
