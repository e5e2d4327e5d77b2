// CSV table parsing with strict typed cells; see csv_table.h.
#include "common/formats/csv_table.h"

#include <sstream>
#include <stdexcept>

#include <fmt/core.h>

#include "common/formats/file_kind.h"
#include "common/formats/file_output.h"
#include "common/formats/format_error.h"
#include "common/formats/input_file.h"
#include "common/formats/number_text.h"

namespace h4 {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

// Splits one line into trimmed cells; quoted cells keep their inner spaces and commas.
std::vector<std::string> SplitLine(std::string_view line, const std::string& source, int line_no) {
  std::vector<std::string> cells;
  size_t i = 0;
  while (true) {
    // Skip leading blanks of the cell.
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string cell;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cell += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        cell += line[i++];
      }
      if (!closed) {
        throw FormatError(source, line_no, "", "unterminated quoted field");
      }
      const size_t comma = line.find(',', i);
      const std::string_view rest =
          line.substr(i, comma == std::string_view::npos ? line.npos : comma - i);
      if (!Trim(rest).empty()) {
        throw FormatError(source, line_no, "",
                          "unexpected text '" + std::string(Trim(rest)) + "' after a quoted field");
      }
      cells.push_back(cell);
      if (comma == std::string_view::npos) break;
      i = comma + 1;
    } else {
      const size_t comma = line.find(',', i);
      cells.emplace_back(
          Trim(line.substr(i, comma == std::string_view::npos ? line.npos : comma - i)));
      if (comma == std::string_view::npos) break;
      i = comma + 1;
    }
  }
  return cells;
}

// A first line of numbers is a row whose header is missing (no format names a column with
// a number): say so, instead of "column appears twice in the header" for "1,0,0,...".
void RejectDataAsHeader(const std::vector<std::string>& cells, const std::string& source_name,
                        int line_no) {
  for (const std::string& cell : cells) {
    double value = 0;
    if (cell.empty() || !ParseDouble(cell, &value)) return;
  }
  throw FormatError(source_name, line_no, "",
                    "the header is missing: the first line holds numbers where the column names "
                    "belong (a data row?)");
}

}  // namespace

CsvTable CsvTable::Parse(const std::string& text, const std::string& source_name) {
  RejectFileKind(text, source_name, {FileKind::kYaml, FileKind::kJson}, "a CSV file");
  CsvTable table;
  table.source_ = source_name;
  std::string_view rest(text);
  // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first column name.
  if (rest.substr(0, 3) == "\xEF\xBB\xBF") rest.remove_prefix(3);
  int line_no = 0;
  while (!rest.empty()) {
    ++line_no;
    const size_t newline = rest.find('\n');
    std::string_view line = rest.substr(0, newline);
    rest = (newline == std::string_view::npos) ? std::string_view() : rest.substr(newline + 1);
    const std::string_view trimmed = Trim(line);
    // Old Mac line ends (CR alone) would read as one long line: say so instead.
    if (trimmed.find('\r') != std::string_view::npos) {
      throw FormatError(source_name, line_no, "",
                        "a carriage return inside a line: line ends must be LF or CRLF, not CR "
                        "alone");
    }
    if (trimmed.empty() || trimmed.front() == '#') continue;
    std::vector<std::string> cells = SplitLine(line, source_name, line_no);
    if (table.header_.empty()) {
      table.header_line_ = line_no;
      RejectDataAsHeader(cells, source_name, line_no);
      for (size_t c = 0; c < cells.size(); ++c) {
        if (cells[c].empty()) {
          throw FormatError(source_name, line_no, "",
                            fmt::format("header column {} has no name", c + 1));
        }
        for (size_t k = 0; k < c; ++k) {
          if (cells[k] == cells[c]) {
            throw FormatError(source_name, line_no, cells[c], "column appears twice in the header");
          }
        }
      }
      table.header_ = std::move(cells);
      continue;
    }
    if (cells.size() < table.header_.size()) {
      throw FormatError(source_name, line_no, table.header_[cells.size()],
                        fmt::format("missing field: the row has {} fields, the header {}",
                                    cells.size(), table.header_.size()));
    }
    if (cells.size() > table.header_.size()) {
      throw FormatError(
          source_name, line_no, "",
          fmt::format("the row has {} fields, the header {}", cells.size(), table.header_.size()));
    }
    table.rows_.push_back({line_no, std::move(cells)});
  }
  if (table.header_.empty()) {
    throw FormatError(source_name, 0, "", "no header line: expected column names");
  }
  return table;
}

CsvTable CsvTable::Read(const std::string& path) { return Parse(ReadTextFile(path), path); }

int CsvTable::ColumnIndex(std::string_view column) const {
  for (size_t c = 0; c < header_.size(); ++c) {
    if (header_[c] == column) return static_cast<int>(c);
  }
  return -1;
}

void CsvTable::RequireColumns(const std::vector<std::string>& columns) const {
  for (const std::string& column : columns) {
    if (!HasColumn(column)) {
      std::string present;
      for (const std::string& name : header_) present += (present.empty() ? "" : ",") + name;
      throw FormatError(source_, header_line_, column,
                        "missing column in the header (it has: " + present + ")");
    }
  }
}

const std::string& CsvTable::Cell(size_t row, std::string_view column) const {
  const int c = ColumnIndex(column);
  if (c < 0) {
    throw FormatError(source_, header_line_, std::string(column), "missing column in the header");
  }
  return rows_[row].cells[static_cast<size_t>(c)];
}

bool CsvTable::IsEmpty(size_t row, std::string_view column) const {
  return !HasColumn(column) || Cell(row, column).empty();
}

int64_t CsvTable::GetInt64(size_t row, std::string_view column) const {
  const std::string& cell = Cell(row, column);
  int64_t value = 0;
  if (!ParseInt64(cell, &value)) Fail(row, column, "expected an integer, got '" + cell + "'");
  return value;
}

double CsvTable::GetDouble(size_t row, std::string_view column) const {
  const std::string& cell = Cell(row, column);
  double value = 0.0;
  if (!ParseDouble(cell, &value)) Fail(row, column, "expected a number, got '" + cell + "'");
  return value;
}

std::optional<double> CsvTable::GetOptionalDouble(size_t row, std::string_view column) const {
  if (IsEmpty(row, column)) return std::nullopt;
  return GetDouble(row, column);
}

std::string CsvTable::GetString(size_t row, std::string_view column) const {
  const std::string& cell = Cell(row, column);
  if (cell.empty()) Fail(row, column, "expected a value, got an empty field");
  return cell;
}

void CsvTable::Fail(size_t row, std::string_view column, const std::string& what) const {
  throw FormatError(source_, rows_[row].line, std::string(column), what);
}

std::string CsvQuote(const std::string& cell) {
  // Rows are lines: a line break inside a cell could not be read back.
  if (cell.find_first_of("\n\r") != std::string::npos) {
    throw std::invalid_argument("cannot write a CSV cell holding a line break: '" + cell + "'");
  }
  const bool needs_quotes =
      cell.find_first_of(",\"") != std::string::npos ||
      (!cell.empty() && (cell.front() == '#' || cell.front() == ' ' || cell.front() == '\t' ||
                         cell.back() == ' ' || cell.back() == '\t'));
  if (!needs_quotes) return cell;
  std::string quoted = "\"";
  for (char c : cell) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

void WriteTextFile(const std::string& path, const std::string& text) {
  WriteFileAtomically(path, text);
}

std::string ReadTextFile(const std::string& path) { return ReadDataFile(path); }

}  // namespace h4
