// A guess, from its first line, at which kind of the project's files a text is, so that a
// file given in the wrong place (robot.yaml and the dataset swapped on a command line) is
// refused with "this looks like a dataset CSV, not a robot.yaml" instead of a parse error
// quoting the file (common/formats/README.md lists the formats).
#pragma once

#include <string>

namespace h4 {

enum class FileKind {
  kUnknown,
  kDatasetCsv,  ///< header starting pose_id,utime,q1 (dataset_csv.h)
  kOtherCsv,    ///< another comma-separated header (poses, joints, board poses)
  kYaml,        ///< "key:" or a YAML directive / document start, no commas
};

FileKind GuessFileKind(const std::string& text);
/// "a dataset CSV", "a CSV file", "a YAML file", "an unknown file".
const char* DescribeFileKind(FileKind kind);

}  // namespace h4
