// A small CSV table shared by the CSV formats (common/formats/README.md): a required header,
// columns in any order, extra columns ignored, blank and '#' comment lines skipped, CRLF tolerated,
// cells trimmed of spaces, RFC 4180 double quotes within a line. Every getter checks its cell
// strictly and throws FormatError(file, line, column, what).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace h4 {

class CsvTable {
 public:
  /// Splits `text` into header and rows; `source_name` (a path) goes into messages.
  /// Throws FormatError on an empty file, a duplicate or empty header name, a row
  /// with more or fewer fields than the header, an unterminated quote, or a
  /// carriage return inside a line (CR-only line ends; LF and CRLF are read).
  static CsvTable Parse(const std::string& text, const std::string& source_name);
  /// Reads the file at `path` and parses it; an unreadable file is a FormatError.
  static CsvTable Read(const std::string& path);

  const std::string& source() const { return source_; }
  int header_line() const { return header_line_; }
  size_t num_rows() const { return rows_.size(); }
  /// 1-based line number of row `row` in the text.
  int line(size_t row) const { return rows_[row].line; }

  bool HasColumn(std::string_view column) const { return ColumnIndex(column) >= 0; }
  /// Throws FormatError(file, header line, column, "missing column ...") for the first
  /// missing one.
  void RequireColumns(const std::vector<std::string>& columns) const;

  /// The trimmed, unquoted cell; a missing column is a FormatError.
  const std::string& Cell(size_t row, std::string_view column) const;
  /// True when the column is absent or the cell is empty.
  bool IsEmpty(size_t row, std::string_view column) const;

  int64_t GetInt64(size_t row, std::string_view column) const;
  double GetDouble(size_t row, std::string_view column) const;
  /// Empty when the column is absent or the cell empty; a non-number is an error.
  std::optional<double> GetOptionalDouble(size_t row, std::string_view column) const;
  /// The cell text; an empty cell is an error ("expected a value").
  std::string GetString(size_t row, std::string_view column) const;

  /// Throws FormatError(file, line of row, column, what).
  [[noreturn]] void Fail(size_t row, std::string_view column, const std::string& what) const;

 private:
  struct Row {
    int line = 0;
    std::vector<std::string> cells;
  };
  int ColumnIndex(std::string_view column) const;

  std::string source_;
  int header_line_ = 0;
  std::vector<std::string> header_;
  std::vector<Row> rows_;
};

/// Quotes a cell for writing when it holds a comma, a quote, a '#' at its start or
/// surrounding spaces (which the reader would otherwise trim).
std::string CsvQuote(const std::string& cell);

/// The table's rows in order, each as read_row(row index) reads it (a parser's loop).
template <typename ReadRow>
auto ReadCsvRows(const CsvTable& table, ReadRow read_row) {
  std::vector<decltype(read_row(size_t{0}))> rows;
  rows.reserve(table.num_rows());
  for (size_t r = 0; r < table.num_rows(); ++r) rows.push_back(read_row(r));
  return rows;
}

/// A CSV text: the `header` line, then a line per row as format_row(row) writes it (without
/// the newline, which this adds), in the order of `rows`.
template <typename Row, typename FormatRow>
std::string FormatCsvLines(std::string_view header, const std::vector<Row>& rows,
                           FormatRow format_row) {
  std::string text(header);
  text += '\n';
  for (const Row& row : rows) {
    text += format_row(row);
    text += '\n';
  }
  return text;
}

/// Replaces `path` with `text` atomically (WriteFileAtomically, file_output.h: a failed
/// write leaves the previous file whole); throws std::runtime_error naming the path.
void WriteTextFile(const std::string& path, const std::string& text);

/// Reads the whole file (ReadDataFile, input_file.h: a regular file of at most
/// kMaxDataFileBytes, opened without waiting on a FIFO); throws FormatError(path, 0, "", ...)
/// when it cannot be read.
std::string ReadTextFile(const std::string& path);

}  // namespace h4
