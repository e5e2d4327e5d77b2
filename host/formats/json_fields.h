// Strict access to JSON values with errors that name the file and the JSON path
// ("parameters[3].value") and what was expected. JSON keeps no line numbers after
// parsing, so semantic errors carry line 0; a syntax error carries the line computed from
// nlohmann's byte offset. Internal to h4::host_formats (nlohmann-json is a private dependency).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace h4 {

/// Deepest nesting of arrays and objects LoadJson accepts (an identification result
/// needs 3).
inline constexpr int kMaxJsonDepth = 64;

/// Parses `text`; a syntax error, or nesting deeper than kMaxJsonDepth (checked before
/// parsing), becomes FormatError(source, line, "", message).
nlohmann::json LoadJson(const std::string& text, const std::string& source_name);

/// A JSON value and its path, for reading fields of it.
class JsonValue {
 public:
  JsonValue(const nlohmann::json& value, std::string source, std::string path)
      : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

  const nlohmann::json& json() const { return *value_; }
  const std::string& path() const { return path_; }

  /// The member `key` of this object (which must be an object); missing is an error.
  JsonValue operator[](const std::string& key) const;
  /// True when this object has `key` with a non-null value.
  bool HasNonNull(const std::string& key) const;
  /// Element `index` of this array.
  JsonValue At(size_t index) const;

  void RequireObject() const;
  /// Number of elements; `count` > 0 requires exactly that many.
  size_t ArraySize(size_t count = 0) const;

  double Number() const;
  double NonNegativeNumber() const;
  std::optional<double> NumberOrNull() const;
  int64_t Integer() const;
  std::string String() const;
  std::vector<double> Numbers(size_t count) const;
  std::vector<int64_t> Integers() const;

  [[noreturn]] void Fail(const std::string& what) const;

 private:
  const nlohmann::json* value_;
  std::string source_;
  std::string path_;
};

}  // namespace h4
