// Path-aware JSON field access; see json_fields.h.
#include "host/formats/json_fields.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "common/formats/file_kind.h"
#include "common/formats/format_error.h"

namespace h4 {
namespace {

// Only called on values of bounded depth (LoadJson refuses deeper documents); invalid
// UTF-8 in a string is shown replaced rather than thrown as nlohmann's own error.
std::string Describe(const nlohmann::json& value) {
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return std::string(value.type_name()) + " " + text;
}

// Refuses a document nested deeper than kMaxJsonDepth before it is parsed: nlohmann's
// dump and destruction recurse over the nesting, so 100,000 levels overflow the stack. One
// pass over the text, brackets inside strings skipped; the error names the line.
void RequireBoundedDepth(const std::string& text, const std::string& source_name) {
  int depth = 0;
  int line = 1;
  bool in_string = false;
  bool escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) {
        throw FormatError(source_name, line, "",
                          fmt::format("JSON nested deeper than {} levels", kMaxJsonDepth));
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string WithoutExceptionId(const nlohmann::json::exception& e) {
  std::string what = e.what();
  const size_t bracket = what.find("] ");
  if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
    what = what.substr(bracket + 2);
  }
  return what;
}

}  // namespace

nlohmann::json LoadJson(const std::string& text, const std::string& source_name) {
  RejectFileKind(text, source_name, {FileKind::kDatasetCsv, FileKind::kOtherCsv, FileKind::kYaml},
                 "a JSON file (an identification result)");
  RequireBoundedDepth(text, source_name);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the offending character.
    const size_t end = std::min(text.size(), e.byte > 0 ? e.byte - 1 : 0);
    const int line =
        1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(end), '\n'));
    throw FormatError(source_name, line, "", "invalid JSON: " + WithoutExceptionId(e));
  } catch (const nlohmann::json::exception& e) {
    // Found by fuzzing: a number beyond double's range ("1e400") is out_of_range.406,
    // which carries no position.
    throw FormatError(source_name, 0, "", "invalid JSON: " + WithoutExceptionId(e));
  }
}

JsonValue JsonValue::operator[](const std::string& key) const {
  RequireObject();
  const std::string path = path_.empty() ? key : path_ + "." + key;
  const auto it = value_->find(key);
  if (it == value_->end()) throw FormatError(source_, 0, path, "missing key");
  return JsonValue(*it, source_, path);
}

bool JsonValue::HasNonNull(const std::string& key) const {
  RequireObject();
  const auto it = value_->find(key);
  return it != value_->end() && !it->is_null();
}

JsonValue JsonValue::At(size_t index) const {
  return JsonValue((*value_)[index], source_, fmt::format("{}[{}]", path_, index));
}

void JsonValue::RequireObject() const {
  if (!value_->is_object()) Fail("expected an object, got " + Describe(*value_));
}

size_t JsonValue::ArraySize(size_t count) const {
  if (!value_->is_array() || (count > 0 && value_->size() != count)) {
    Fail("expected an array" + (count > 0 ? fmt::format(" of {}", count) : std::string()) +
         ", got " + Describe(*value_));
  }
  return value_->size();
}

double JsonValue::Number() const {
  if (!value_->is_number()) Fail("expected a number, got " + Describe(*value_));
  const double value = value_->get<double>();
  if (!std::isfinite(value)) Fail("expected a finite number, got " + Describe(*value_));
  return value;
}

double JsonValue::NonNegativeNumber() const {
  const double value = Number();
  if (value < 0.0) Fail("expected a non-negative number, got " + Describe(*value_));
  return value;
}

std::optional<double> JsonValue::NumberOrNull() const {
  if (value_->is_null()) return std::nullopt;
  return Number();
}

int64_t JsonValue::Integer() const {
  if (value_->is_number_integer() &&
      (!value_->is_number_unsigned() ||
       value_->get<uint64_t>() <= static_cast<uint64_t>(INT64_MAX))) {
    return value_->get<int64_t>();
  }
  Fail("expected an integer, got " + Describe(*value_));
}

std::string JsonValue::String() const {
  if (!value_->is_string()) Fail("expected a string, got " + Describe(*value_));
  return value_->get<std::string>();
}

std::vector<double> JsonValue::Numbers(size_t count) const {
  ArraySize(count);
  std::vector<double> values;
  for (size_t i = 0; i < count; ++i) values.push_back(At(i).Number());
  return values;
}

std::vector<int64_t> JsonValue::Integers() const {
  const size_t n = ArraySize();
  std::vector<int64_t> values;
  for (size_t i = 0; i < n; ++i) values.push_back(At(i).Integer());
  return values;
}

void JsonValue::Fail(const std::string& what) const { throw FormatError(source_, 0, path_, what); }

}  // namespace h4
