// The report's table rows as HTML: a header row, and a row whose first cell is a header.
// Cells are HTML already (callers escape text with MarkupEscape).
#pragma once

#include <cctype>
#include <string>
#include <vector>

namespace h4::host {

/// `text` with every number that rounded to zero written without its sign: "-0.0000" and
/// "-0" become "0.0000" and "0" ("-0.0012", "-10", "1e-05" and a name such as "run-0.csv"
/// stay), as a table should read.
inline std::string WithoutNegativeZeros(std::string text) {
  const auto word = [&text](size_t i) {  // part of a number or a name
    if (i >= text.size()) return false;
    const unsigned char c = static_cast<unsigned char>(text[i]);
    return std::isalnum(c) != 0 || c == '_' || c == '.';
  };
  for (size_t at = text.find("-0"); at != std::string::npos; at = text.find("-0", at + 1)) {
    if (at > 0 && word(at - 1)) continue;  // "1-0", "e-05", "run-0"
    size_t end = at + 2;
    if (end < text.size() && text[end] == '.') {
      ++end;
      while (end < text.size() && text[end] == '0') ++end;
    }
    if (!word(end)) text.erase(at, 1);  // all zeros, not part of a name: drop the sign
  }
  return text;
}

inline std::string Row(const std::string& head, const std::vector<std::string>& cells,
                       const std::string& css_class = "") {
  std::string row = css_class.empty() ? "<tr>" : "<tr class=\"" + css_class + "\">";
  row += "<th>" + head + "</th>";
  for (const auto& c : cells) row += "<td>" + WithoutNegativeZeros(c) + "</td>";
  return row + "</tr>\n";
}

inline std::string Header(const std::vector<std::string>& cells) {
  std::string row = "<tr>";
  for (const auto& c : cells) row += "<th>" + c + "</th>";
  return row + "</tr>\n";
}

}  // namespace h4::host
