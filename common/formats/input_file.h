// Reading an input file without hanging and without reading it past what it can be: every
// reader of a data file (CSV, YAML, JSON, images, the bus's key file) opens it here
// (common/formats/README.md#reading-files). The file is opened without waiting (a FIFO or
// a device would otherwise block open() until a writer comes, or be read forever, as
// /dev/zero is), checked on the opened descriptor (fstat: the file read is the file
// checked) to be a regular file of at most the reader's limit, then read whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace h4 {

/// The largest data file (CSV, YAML, JSON) a reader takes: 64 MiB. A corners CSV of 5000
/// poses x 144 corners, the largest a campaign writes, is about 40 MB; the other formats
/// are far smaller.
inline constexpr size_t kMaxDataFileBytes = size_t{64} << 20;

/// A regular file opened for reading (O_NONBLOCK, O_CLOEXEC, O_NOCTTY) and checked with
/// fstat; ok() false with error() ("not a regular file (a FIFO)", "cannot open: No such
/// file or directory") otherwise. error() does not repeat the path.
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  /// Size and permission bits (st_mode & 07777) at opening; 0 when !ok().
  int64_t size() const { return size_; }
  unsigned mode() const { return mode_; }

  /// The whole file; false with error() when !ok(), when the file holds more than
  /// max_bytes ("70000000 bytes; a ... file holds at most 67108864"), or when the read
  /// fails or comes short.
  bool ReadAll(size_t max_bytes, std::string* bytes);
  /// At most the first max_bytes of the file (a header); false with error() on a failed read.
  bool ReadPrefix(size_t max_bytes, std::string* bytes);

 private:
  bool Read(size_t count, std::string* bytes);

  int fd_ = -1;
  int64_t size_ = 0;
  unsigned mode_ = 0;
  std::string error_;
};

/// Reads the whole of `path` (InputFile) as a data file of at most max_bytes; throws
/// FormatError(path, 0, "", why) when it cannot.
std::string ReadDataFile(const std::string& path, size_t max_bytes = kMaxDataFileBytes);

}  // namespace h4
