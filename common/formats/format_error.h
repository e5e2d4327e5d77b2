// The one error type every reader throws: it names the file, the line (1-based, 0
// when the problem is not on one line), the field, and what was expected.
#pragma once

#include <stdexcept>
#include <string>

namespace h4 {

class FormatError : public std::runtime_error {
 public:
  /// Message: "<file>:<line>: field '<field>': <what>" (line and field omitted when
  /// empty/0), e.g. "data.csv:12: field 'qw': expected a number, got 'abc'".
  FormatError(std::string file, int line, std::string field, const std::string& what);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  std::string field_;
};

}  // namespace h4
