// A guess, from its first line, at which kind of the project's files a text is, so that a
// file given in the wrong place (robot.yaml and the dataset swapped on a command line) is
// refused with "this looks like a dataset CSV, not a robot.yaml" instead of a parse error
// quoting the file (common/formats/README.md lists the formats).
#pragma once

#include <initializer_list>
#include <string>

namespace h4 {

/// Described by DescribeFileKind, in this order (file_kind.cpp).
enum class FileKind {
  kUnknown,
  kDatasetCsv,  ///< header starting pose_id,utime,q1 (dataset_csv.h)
  kOtherCsv,    ///< another comma-separated header (poses, joints, board poses)
  kYaml,        ///< "key:" or a YAML directive / document start, no commas
  kJson,        ///< starts with '{' or '[' (an identification result)
};

FileKind GuessFileKind(const std::string& text);
/// "a dataset CSV", "a CSV file", "a YAML file", "an unknown file".
const char* DescribeFileKind(FileKind kind);

/// Throws FormatError "<source>:1: this looks like <its kind>, not <expected>" when the
/// text's first line shows one of the `refused` kinds: one line naming the mix-up, instead
/// of a parser's error that may quote the whole file.
void RejectFileKind(const std::string& text, const std::string& source_name,
                    std::initializer_list<FileKind> refused, const std::string& expected);

}  // namespace h4
