// Strict text <-> number conversions shared by every reader and writer: a number is
// the whole field or nothing ("1.0abc", "", "nan", "inf" are rejected), and doubles are
// written in the shortest form that reads back to the same value.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace h4 {

/// Parses a finite decimal number (optional sign, digits, fraction, exponent) that
/// fills `text` exactly. Returns false (leaving *value unchanged) otherwise.
bool ParseDouble(std::string_view text, double* value);

/// Parses a decimal integer (optional sign) that fills `text` exactly and fits int64.
bool ParseInt64(std::string_view text, int64_t* value);

/// Shortest decimal text that reads back to exactly `value` (std::to_chars).
/// Throws std::invalid_argument naming `field` when `value` is not finite: the
/// formats never carry NaN or infinity.
std::string FormatDouble(double value, std::string_view field);

}  // namespace h4
