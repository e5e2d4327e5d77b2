// Strict access to the YAML files (robot, board, camera): a YAML mapping that knows its
// source file and its path in the document, so that every error names the file, the
// 1-based line (from yaml-cpp's marks) and the field ("model12.alpha[2]"), and what was
// expected. Numbers go through the strict parsers of number_text.h (".nan", "1.0abc" are
// errors); a key given twice is an error rather than yaml-cpp's silent first-wins.
// Internal to h4::common (yaml-cpp is a private dependency).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace h4 {

/// Deepest nesting LoadYaml accepts (flow brackets, or compact "- - x" indicators on one
/// line), and the deepest indentation (columns): yaml-cpp recurses once per level.
inline constexpr int kMaxYamlDepth = 64;
inline constexpr size_t kMaxYamlIndent = 256;

/// Parses YAML text; a syntax error, or nesting beyond kMaxYamlDepth / kMaxYamlIndent
/// (checked before parsing), becomes a FormatError with the line.
YAML::Node LoadYaml(const std::string& text, const std::string& source_name);

class YamlMap {
 public:
  /// `node` must be a mapping; `path` is its field path ("" for the document root) and
  /// `line` the line to report when the node itself has no mark (0: none).
  YamlMap(const YAML::Node& node, std::string source, std::string path, int line);

  bool Has(const std::string& key) const;
  /// The value at `key`; a missing key is an error on this mapping's line.
  YAML::Node Get(const std::string& key) const;
  YamlMap Map(const std::string& key) const;

  double Double(const std::string& key) const;
  /// Strictly positive number (lengths, sizes).
  double PositiveDouble(const std::string& key) const;
  int64_t Int(const std::string& key) const;
  std::string String(const std::string& key) const;
  /// A flow or block list of exactly `count` numbers.
  std::vector<double> Doubles(const std::string& key, size_t count) const;
  /// A list of `count` integers, or of any length when count is 0.
  std::vector<int64_t> Ints(const std::string& key, size_t count) const;

  /// Throws on the first key not in `known` (for the blocks a format owns, where an unknown
  /// key can only be a mistake: a misspelt optional key would silently take its default).
  void RejectUnknownKeys(const std::vector<std::string>& known) const;
  /// Throws on a key that equals one of `known` except for letter case ("firstID"): where
  /// extra keys are allowed, such a key would otherwise be ignored and its default used.
  void RejectCaseVariants(const std::vector<std::string>& known) const;

  /// "path.key" (or "key" at the root).
  std::string FieldOf(const std::string& key) const;
  /// Line of the value at `key` (1-based), else of the key, else of this mapping.
  int LineOf(const std::string& key) const;
  int line() const { return line_; }
  const std::string& source() const { return source_; }
  /// Throws FormatError(source, LineOf(key), FieldOf(key), what).
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const;
  /// Same for element `index` of the list at `key` (field "key[index]", its own line).
  [[noreturn]] void FailElement(const std::string& key, size_t index,
                                const std::string& what) const;

 private:
  YAML::Node node_;
  std::string source_;
  std::string path_;
  int line_;
};

/// A scalar node's text as a strict number; `field`/`line` name it in the error.
double YamlScalarDouble(const YAML::Node& node, const std::string& source, const std::string& field,
                        int line);
int64_t YamlScalarInt(const YAML::Node& node, const std::string& source, const std::string& field,
                      int line);

/// 1-based line of a node, or `fallback` when it has no mark.
int YamlLine(const YAML::Node& node, int fallback);

}  // namespace h4
