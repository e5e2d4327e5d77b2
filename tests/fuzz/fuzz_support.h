// Shared by the fuzz targets (tests/fuzz/README.md): the input as text, given to a parser
// under a source name. A FormatError is the parser's documented way to refuse input and
// is expected; any other exception, a crash, a leak, undefined behaviour, a hang or an
// allocation beyond libFuzzer's limits is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "common/formats/format_error.h"

namespace h4::fuzz {

/// The fuzzer's bytes as the text a file would hold.
inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// `parse(text)`'s value, or nothing when it throws FormatError.
template <typename Parse>
auto ParseOrRefuse(const std::string& text, Parse&& parse) -> std::optional<decltype(parse(text))> {
  try {
    return parse(text);
  } catch (const FormatError&) {
    return std::nullopt;
  }
}

/// A property that must hold for every input the parser accepted (a round trip): its
/// failure aborts, which libFuzzer reports with the input.
inline void Require(bool holds, const char* what) {
  if (holds) return;
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  std::abort();
}

/// The round trip of rows the parser accepted: `back` (what it read of what was written)
/// holds as many rows as `rows`, and `same(back[i], rows[i])` for each; `what` names the
/// round trip in the failure ("... keeps every row", "... keeps the values").
template <typename Rows, typename Same>
void RequireRoundTrip(const Rows& rows, const Rows& back, Same&& same, const std::string& what) {
  if (back.size() != rows.size()) Require(false, (what + " keeps every row").c_str());
  for (size_t i = 0; i < back.size(); ++i) {
    if (!same(back[i], rows[i])) Require(false, (what + " keeps the values").c_str());
  }
}

}  // namespace h4::fuzz
