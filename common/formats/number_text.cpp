// Strict number parsing and shortest round-trip formatting; see number_text.h.
#include "common/formats/number_text.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace h4 {
namespace {

// std::from_chars has no leading '+'; accept exactly one, as strtod and YAML do.
std::string_view StripPlus(std::string_view text) {
  if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') {
    return text.substr(1);
  }
  return text;
}

}  // namespace

bool ParseDouble(std::string_view text, double* value) {
  text = StripPlus(text);
  if (text.empty()) return false;
  // from_chars also reads "nan", "inf" and "infinity": the first character must be a
  // digit, a '.', or a '-' followed by one of them.
  const size_t first = (text[0] == '-') ? 1 : 0;
  if (first >= text.size()) return false;
  const char c = text[first];
  if (!((c >= '0' && c <= '9') || c == '.')) return false;
  double parsed = 0.0;
  const auto [end, error] =
      std::from_chars(text.data(), text.data() + text.size(), parsed, std::chars_format::general);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(parsed)) {
    return false;
  }
  *value = parsed;
  return true;
}

bool ParseInt64(std::string_view text, int64_t* value) {
  text = StripPlus(text);
  if (text.empty()) return false;
  int64_t parsed = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed, 10);
  if (error != std::errc() || end != text.data() + text.size()) return false;
  *value = parsed;
  return true;
}

std::string FormatDouble(double value, std::string_view field) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument("cannot write field '" + std::string(field) +
                                "': value is not finite");
  }
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (error != std::errc()) throw std::invalid_argument("cannot format a double");
  return std::string(buffer, end);
}

}  // namespace h4
