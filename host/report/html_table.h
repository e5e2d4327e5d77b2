// The report's table rows as HTML: a header row, and a row whose first cell is a header.
// Cells are HTML already (callers escape text with MarkupEscape).
#pragma once

#include <string>
#include <vector>

namespace h4::host {

inline std::string Row(const std::string& head, const std::vector<std::string>& cells,
                       const std::string& css_class = "") {
  std::string row = css_class.empty() ? "<tr>" : "<tr class=\"" + css_class + "\">";
  row += "<th>" + head + "</th>";
  for (const auto& c : cells) row += "<td>" + c + "</td>";
  return row + "</tr>\n";
}

inline std::string Header(const std::vector<std::string>& cells) {
  std::string row = "<tr>";
  for (const auto& c : cells) row += "<th>" + c + "</th>";
  return row + "</tr>\n";
}

}  // namespace h4::host
