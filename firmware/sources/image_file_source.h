// Frames from image files (PNG, JPEG, PGM...): a list of files and/or directories (a
// directory gives its image files sorted by name). Colour images are converted to grey;
// 16-bit images are refused with a message naming the file (the pipeline measures 8-bit
// frames, and silently scaling would change the noise model).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/formats/image_size.h"
#include "firmware/frames/frame_source.h"

namespace h4::cam {

/// A file that starts as a JPEG (FF D8) but does not end with its end-of-image marker
/// (FF D9, trailing zero bytes allowed): a copy cut short, which libjpeg would decode with
/// a warning and grey in place of the missing part.
bool IsTruncatedJpeg(const std::vector<uint8_t>& bytes);

class ImageFileSource final : public DevicelessFrameSource {
 public:
  explicit ImageFileSource(std::vector<std::string> paths);

  /// Expands directories and checks that every file exists; false with error() otherwise
  /// (including when no image file is found).
  bool Open() override;
  /// The next file as a grey frame (utime = file modification time, origin = path).
  /// nullopt with error() set on an unreadable/unsupported file (the source then moves
  /// on to the next file), nullopt with finished() at the end.
  std::optional<Frame> Next(std::chrono::milliseconds timeout) override;

  std::string Describe() const override;
  bool finished() const override { return next_ >= files_.size() && opened_; }
  /// The files, in the order they are delivered (after Open()).
  const std::vector<std::string>& files() const { return files_; }

  /// Reads one image file as CV_8UC1; empty with `why` set when it cannot: not a regular
  /// file or over kMaxImageFileBytes (common/formats/input_file.h), then as DecodeGrey.
  static cv::Mat ReadGrey(const std::string& path, std::string* why);
  /// An image file's bytes as CV_8UC1: the size its header declares checked against the
  /// image size limits (common/formats/image_size.h) before anything is decoded, a truncated
  /// JPEG refused, then decoded (cv::imdecode, IMREAD_UNCHANGED) and made grey (ToGrey);
  /// empty with `why` (naming `name`) when it cannot.
  static cv::Mat DecodeGrey(const std::string& bytes, const std::string& name, std::string* why);
  /// The size an image file's header declares, within the limits; nullopt with `why`
  /// otherwise. Reads at most kImageHeaderBytes.
  static std::optional<ImageHeaderSize> HeaderSize(const std::string& path, std::string* why);
  /// A decoded image (cv::imread / cv::imdecode with IMREAD_UNCHANGED) as CV_8UC1: grey
  /// kept, colour (3 or 4 channels) converted; empty with `why` (naming `name`) for an
  /// empty image, a depth other than 8 bits or another channel count.
  static cv::Mat ToGrey(const cv::Mat& image, const std::string& name, std::string* why);

 private:
  static std::optional<ImageHeaderSize> CheckedSize(std::string_view bytes,
                                                    const std::string& name, std::string* why);

  std::vector<std::string> paths_;
  std::vector<std::string> files_;
  size_t next_ = 0;
  bool opened_ = false;
};

}  // namespace h4::cam
