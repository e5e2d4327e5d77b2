// Strict YAML mapping access with file/line/field errors; see yaml_map.h.
#include "common/formats/yaml_map.h"

#include <algorithm>
#include <cctype>
#include <map>

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

}  // namespace

YAML::Node LoadYaml(const std::string& text, const std::string& source_name) {
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

double YamlScalarDouble(const YAML::Node& node, const std::string& source, const std::string& field,
                        int line) {
  double value = 0.0;
  if (!node.IsScalar() || !ParseDouble(node.Scalar(), &value)) {
    throw FormatError(source, line, field, "expected a number, got " + Describe(node));
  }
  return value;
}

int64_t YamlScalarInt(const YAML::Node& node, const std::string& source, const std::string& field,
                      int line) {
  int64_t value = 0;
  if (!node.IsScalar() || !ParseInt64(node.Scalar(), &value)) {
    throw FormatError(source, line, field, "expected an integer, got " + Describe(node));
  }
  return value;
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
                        "key given twice (first on line " + std::to_string(previous->second) + ")");
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
  throw FormatError(source_, line, FieldOf(key) + "[" + std::to_string(index) + "]", what);
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
    Fail(key,
         "expected a list of " + std::to_string(count) + " numbers, got " +
             (list.IsSequence() ? "a list of " + std::to_string(list.size()) : Describe(list)));
  }
  std::vector<double> values;
  for (size_t i = 0; i < count; ++i) {
    values.push_back(YamlScalarDouble(list[i], source_,
                                      FieldOf(key) + "[" + std::to_string(i) + "]",
                                      YamlLine(list[i], LineOf(key))));
  }
  return values;
}

std::vector<int64_t> YamlMap::Ints(const std::string& key, size_t count) const {
  const YAML::Node list = Get(key);
  if (!list.IsSequence() || (count > 0 && list.size() != count)) {
    Fail(key,
         "expected a list of " + (count > 0 ? std::to_string(count) + " " : std::string()) +
             "integers, got " +
             (list.IsSequence() ? "a list of " + std::to_string(list.size()) : Describe(list)));
  }
  std::vector<int64_t> values;
  for (size_t i = 0; i < list.size(); ++i) {
    values.push_back(YamlScalarInt(list[i], source_, FieldOf(key) + "[" + std::to_string(i) + "]",
                                   YamlLine(list[i], LineOf(key))));
  }
  return values;
}

}  // namespace h4
