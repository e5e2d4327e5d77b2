// Strict YAML mapping access with file/line/field errors; see yaml_map.h.
#include "common/formats/yaml_map.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <string_view>

#include <fmt/core.h>

#include "common/formats/file_kind.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"

namespace h4 {
namespace {

std::string Describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "'" + node.Scalar() + "'";
}

// yaml-cpp 0.7 parses nested collections recursively and has no depth limit: a document
// nested 100,000 deep overflows the stack. Nesting comes from flow brackets (counted
// across lines, outside quotes and comments), from indentation, and from compact
// indicators at the start of a line ("- - - x"); each is bounded before parsing. A bracket
// in a plain or block scalar counts too: only a file with more than kMaxYamlDepth of them
// open is refused, which no file of ours has.
class YamlDepthCheck {
 public:
  explicit YamlDepthCheck(const std::string& source_name) : source_(source_name) {}

  // Quotes are followed within a line only (so an apostrophe in a plain scalar cannot
  // hide the lines after it); a quote opens after a space, a bracket, ',' or ':'.
  void Line(std::string_view line) {
    ++line_no_;
    char quote = 0;
    // Checked in flow context too: a '[' in a plain scalar looks like an open bracket.
    const size_t start = BlockIndent(line);
    for (size_t i = start; i < line.size(); ++i) {
      const char c = line[i];
      if (quote != 0) {
        if (c == '\\' && quote == '"') {
          ++i;  // an escaped character
        } else if (c == quote) {
          quote = 0;
        }
        continue;
      }
      const char before = i == start ? ' ' : line[i - 1];
      const bool after_separator =
          std::string_view(" \t[{,:").find(before) != std::string_view::npos;
      if (c == '#' && (before == ' ' || before == '\t')) return;
      if ((c == '"' || c == '\'') && after_separator) quote = c;
      if (c == '[' || c == '{') Require(++flow_ <= kMaxYamlDepth, "flow collections nested");
      if ((c == ']' || c == '}') && flow_ > 0) --flow_;
    }
  }

 private:
  // Skips the indentation and the compact indicators of a block line; returns where the
  // content starts.
  size_t BlockIndent(std::string_view line) {
    size_t i = 0;
    while (i < line.size() && line[i] == ' ') ++i;
    Require(i <= kMaxYamlIndent, "a line indented");
    int indicators = 0;
    while (i < line.size() && (line[i] == '-' || line[i] == '?' || line[i] == ':') &&
           (i + 1 == line.size() || line[i + 1] == ' ' || line[i + 1] == '\t')) {
      Require(++indicators <= kMaxYamlDepth, "block collections nested");
      ++i;
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    }
    return i;
  }

  void Require(bool within, const std::string& what) const {
    if (within) return;
    throw FormatError(source_, line_no_, "",
                      fmt::format("{} deeper than the limit ({} levels, {} columns)", what,
                                  kMaxYamlDepth, kMaxYamlIndent));
  }

  std::string source_;
  int line_no_ = 0;
  int flow_ = 0;
};

void RequireBoundedYamlDepth(const std::string& text, const std::string& source_name) {
  YamlDepthCheck check(source_name);
  std::string_view rest(text);
  while (!rest.empty()) {
    const size_t end = rest.find('\n');
    check.Line(rest.substr(0, end));
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
  }
}

}  // namespace

YAML::Node LoadYaml(const std::string& text, const std::string& source_name) {
  // A CSV parses as one long YAML scalar, and the error would quote all of it.
  RejectFileKind(text, source_name, {FileKind::kDatasetCsv, FileKind::kOtherCsv}, "a YAML file");
  RequireBoundedYamlDepth(text, source_name);
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw FormatError(source_name, e.mark.is_null() ? 0 : e.mark.line + 1, "",
                      "invalid YAML: " + e.msg);
  }
}

int YamlLine(const YAML::Node& node, int fallback) {
  if (!node.IsDefined()) return fallback;
  const YAML::Mark mark = node.Mark();
  return mark.is_null() || mark.line < 0 ? fallback : mark.line + 1;
}

namespace {

/// The scalar `node` as `parse` reads it; else a FormatError "expected <what>, got ...".
template <typename Value>
Value ParsedYamlScalar(const YAML::Node& node, const std::string& source, const std::string& field,
                       int line, bool (*parse)(std::string_view, Value*), const std::string& what) {
  Value value{};
  if (!node.IsScalar() || !parse(node.Scalar(), &value)) {
    throw FormatError(source, line, field, "expected " + what + ", got " + Describe(node));
  }
  return value;
}

}  // namespace

double YamlScalarDouble(const YAML::Node& node, const std::string& source, const std::string& field,
                        int line) {
  return ParsedYamlScalar(node, source, field, line, ParseDouble, "a number");
}

int64_t YamlScalarInt(const YAML::Node& node, const std::string& source, const std::string& field,
                      int line) {
  return ParsedYamlScalar(node, source, field, line, ParseInt64, "an integer");
}

YamlMap::YamlMap(const YAML::Node& node, std::string source, std::string path, int line)
    : node_(node), source_(std::move(source)), path_(std::move(path)), line_(line) {
  if (!node_.IsMap()) {
    throw FormatError(source_, YamlLine(node_, line_), path_,
                      "expected a mapping of keys to values, got " + Describe(node_));
  }
  std::map<std::string, int> first_line;
  for (const auto& entry : node_) {
    const int key_line = YamlLine(entry.first, line_);
    if (!entry.first.IsScalar()) {
      throw FormatError(source_, key_line, path_,
                        "expected a plain key, got " + Describe(entry.first));
    }
    const auto [previous, inserted] = first_line.emplace(entry.first.Scalar(), key_line);
    if (!inserted) {
      throw FormatError(source_, key_line, FieldOf(entry.first.Scalar()),
                        fmt::format("key given twice (first on line {})", previous->second));
    }
  }
}

bool YamlMap::Has(const std::string& key) const {
  for (const auto& entry : node_) {
    if (entry.first.Scalar() == key) return true;
  }
  return false;
}

YAML::Node YamlMap::Get(const std::string& key) const {
  for (const auto& entry : node_) {
    if (entry.first.Scalar() == key) return entry.second;
  }
  throw FormatError(source_, line_, FieldOf(key), "missing key");
}

void YamlMap::RejectUnknownKeys(const std::vector<std::string>& known) const {
  for (const auto& entry : node_) {
    const std::string& key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string names;
    for (const std::string& name : known) names += (names.empty() ? "" : ", ") + name;
    throw FormatError(source_, YamlLine(entry.first, line_), FieldOf(key),
                      "unknown key, expected one of: " + names);
  }
}

void YamlMap::RejectCaseVariants(const std::vector<std::string>& known) const {
  const auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  for (const auto& entry : node_) {
    const std::string& key = entry.first.Scalar();
    for (const std::string& name : known) {
      if (key != name && lower(key) == lower(name)) {
        throw FormatError(source_, YamlLine(entry.first, line_), FieldOf(key),
                          "unknown key; the key names are case-sensitive: '" + name + "'");
      }
    }
  }
}

std::string YamlMap::FieldOf(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

int YamlMap::LineOf(const std::string& key) const {
  for (const auto& entry : node_) {
    if (entry.first.Scalar() != key) continue;
    const int key_line = YamlLine(entry.first, line_);
    // A null value's mark points at the next token: report the key's line instead.
    return entry.second.IsNull() ? key_line : YamlLine(entry.second, key_line);
  }
  return line_;
}

void YamlMap::Fail(const std::string& key, const std::string& what) const {
  throw FormatError(source_, LineOf(key), FieldOf(key), what);
}

void YamlMap::FailElement(const std::string& key, size_t index, const std::string& what) const {
  const YAML::Node list = Get(key);
  const int line =
      list.IsSequence() && index < list.size() ? YamlLine(list[index], LineOf(key)) : LineOf(key);
  throw FormatError(source_, line, fmt::format("{}[{}]", FieldOf(key), index), what);
}

YamlMap YamlMap::Map(const std::string& key) const {
  const YAML::Node value = Get(key);
  int key_line = line_;
  for (const auto& entry : node_) {
    if (entry.first.Scalar() == key) key_line = YamlLine(entry.first, line_);
  }
  return YamlMap(value, source_, FieldOf(key), key_line);
}

double YamlMap::Double(const std::string& key) const {
  return YamlScalarDouble(Get(key), source_, FieldOf(key), LineOf(key));
}

double YamlMap::PositiveDouble(const std::string& key) const {
  const double value = Double(key);
  if (!(value > 0.0)) Fail(key, "expected a positive number, got " + Get(key).Scalar());
  return value;
}

int64_t YamlMap::Int(const std::string& key) const {
  return YamlScalarInt(Get(key), source_, FieldOf(key), LineOf(key));
}

std::string YamlMap::String(const std::string& key) const {
  const YAML::Node value = Get(key);
  if (!value.IsScalar() || value.Scalar().empty()) {
    Fail(key, "expected a name, got " + Describe(value));
  }
  return value.Scalar();
}

std::vector<double> YamlMap::Doubles(const std::string& key, size_t count) const {
  const YAML::Node list = Get(key);
  if (!list.IsSequence() || list.size() != count) {
    Fail(key, fmt::format(
                  "expected a list of {} numbers, got {}", count,
                  (list.IsSequence() ? fmt::format("a list of {}", list.size()) : Describe(list))));
  }
  std::vector<double> values;
  for (size_t i = 0; i < count; ++i) {
    values.push_back(YamlScalarDouble(list[i], source_, fmt::format("{}[{}]", FieldOf(key), i),
                                      YamlLine(list[i], LineOf(key))));
  }
  return values;
}

std::vector<int64_t> YamlMap::Ints(const std::string& key, size_t count) const {
  const YAML::Node list = Get(key);
  if (!list.IsSequence() || (count > 0 && list.size() != count)) {
    Fail(key, "expected a list of " + (count > 0 ? fmt::format("{} ", count) : std::string()) +
                  "integers, got " +
                  (list.IsSequence() ? fmt::format("a list of {}", list.size()) : Describe(list)));
  }
  std::vector<int64_t> values;
  for (size_t i = 0; i < list.size(); ++i) {
    values.push_back(YamlScalarInt(list[i], source_, fmt::format("{}[{}]", FieldOf(key), i),
                                   YamlLine(list[i], LineOf(key))));
  }
  return values;
}

}  // namespace h4
