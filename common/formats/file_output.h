// Writing output files without losing what was there, and refusing an output that is one
// of the command's inputs. Every result, report, export and CSV writer goes through
// WriteFileAtomically: the bytes go to a temporary file in the same directory, are
// flushed to disk (fsync), then renamed over the target, so a crash, a full disk or a
// failed write leaves the previous file whole (common/formats/README.md#writing-files).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace h4 {

/// Replaces `path` with `bytes` atomically: temporary file `.<name>.tmp-<pid>-<n>` beside
/// it (created with mode 0666 minus the umask), write, fsync, rename, fsync of the
/// directory. On any failure the temporary file is removed, `path` is untouched, and a
/// std::runtime_error names `path` and the system's reason. A symbolic link's target is
/// replaced (the link stays); a device or pipe (/dev/stdout) is written in place.
void WriteFileAtomically(const std::string& path, const std::string& bytes);

/// True when `a` and `b` name the same file: the same device and inode when both exist
/// (hard links, symbolic links, "./x" and "x"), else the same canonical path.
bool IsSameFile(const std::string& a, const std::string& b);

/// A command-line file and the option that named it, e.g. {"--data", "dataset.csv"}.
struct NamedPath {
  std::string option;
  std::string path;
};

/// Throws std::invalid_argument when `output` is the same file as one of `inputs` (empty
/// paths are skipped): "--out d.csv is the same file as --data d.csv: refusing to
/// overwrite an input".
void RequireOutputIsNotAnInput(const NamedPath& output, const std::vector<NamedPath>& inputs);

/// Throws std::invalid_argument when the folder `output` is to be written into does not
/// exist: "--out out/camera.yaml: the folder out does not exist (create it first)". For a
/// command that works long before it writes (calibrate-intrinsics), checked first.
void RequireOutputFolder(const NamedPath& output);

}  // namespace h4
