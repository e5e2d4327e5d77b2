// Guessing a file's kind from its first line; see file_kind.h.
#include "common/formats/file_kind.h"

#include <algorithm>

#include "common/formats/format_error.h"
#include "common/text/enum_names.h"

namespace h4 {
namespace {

/// The first line that is neither empty nor a '#' comment, without its line break.
std::string FirstContentLine(const std::string& text) {
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] != '#') return line;
    start = end + 1;
  }
  return "";
}

}  // namespace

FileKind GuessFileKind(const std::string& text) {
  const std::string line = FirstContentLine(text);
  const auto commas = std::count(line.begin(), line.end(), ',');
  if (line.rfind("pose_id,utime,q1", 0) == 0) return FileKind::kDatasetCsv;
  if (!line.empty() && (line[0] == '{' || line[0] == '[')) return FileKind::kJson;
  if (commas >= 2 && line.find(':') == std::string::npos) return FileKind::kOtherCsv;
  if (line.rfind("%YAML", 0) == 0 || line == "---" ||
      (commas == 0 && line.find(':') != std::string::npos)) {
    return FileKind::kYaml;
  }
  return FileKind::kUnknown;
}

constexpr EnumNames<FileKind, FileKind::kJson> kFileKindDescriptions = {
    "an unknown file", "a dataset CSV", "a CSV file", "a YAML file", "a JSON file"};

const char* DescribeFileKind(FileKind kind) {
  return kFileKindDescriptions.NameOf(kind, "an unknown file");
}

void RejectFileKind(const std::string& text, const std::string& source_name,
                    std::initializer_list<FileKind> refused, const std::string& expected) {
  const FileKind kind = GuessFileKind(text);
  if (std::find(refused.begin(), refused.end(), kind) == refused.end()) return;
  throw FormatError(source_name, 1, "",
                    std::string("this looks like ") + DescribeFileKind(kind) + ", not " + expected);
}

}  // namespace h4
