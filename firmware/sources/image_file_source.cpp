// Image files as frames; see image_file_source.h.
#include "firmware/sources/image_file_source.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <set>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/formats/input_file.h"

namespace h4::cam {
namespace fs = std::filesystem;

namespace {

bool IsImageName(const fs::path& path) {
  static const std::set<std::string> kExtensions = {".png", ".jpg", ".jpeg", ".pgm", ".ppm",
                                                    ".pnm", ".bmp", ".tif",  ".tiff"};
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return kExtensions.count(ext) > 0;
}

}  // namespace

bool IsTruncatedJpeg(const std::vector<uint8_t>& bytes) {
  if (bytes.size() < 2 || bytes[0] != 0xFF || bytes[1] != 0xD8) return false;  // not a JPEG
  // libjpeg decodes a JPEG cut short (it warns "Premature end of JPEG file" and fills the
  // rest grey), so a half-copied file would be measured: a whole one ends with the EOI
  // marker, after at most some zero padding that some writers add.
  size_t end = bytes.size();
  while (end > 2 && bytes[end - 1] == 0x00) --end;
  return !(end >= 4 && bytes[end - 2] == 0xFF && bytes[end - 1] == 0xD9);
}

ImageFileSource::ImageFileSource(std::vector<std::string> paths) : paths_(std::move(paths)) {}

bool ImageFileSource::Open() {
  files_.clear();
  next_ = 0;
  error_.clear();
  for (const std::string& path : paths_) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      std::vector<std::string> found;
      for (const auto& entry : fs::directory_iterator(path, ec)) {
        if (entry.is_regular_file() && IsImageName(entry.path())) {
          found.push_back(entry.path().string());
        }
      }
      std::sort(found.begin(), found.end());
      files_.insert(files_.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(path, ec)) {
      files_.push_back(path);
    } else if (fs::exists(path, ec)) {
      // A FIFO or a device named as an image: refused as the reader would (input_file.h).
      error_ = path + ": not a regular file";
      return false;
    } else {
      error_ = path + ": no such file or directory";
      return false;
    }
  }
  if (files_.empty()) {
    error_ = "no image file (png, jpg, pgm, ...) in the given paths";
    return false;
  }
  opened_ = true;
  return true;
}

std::optional<ImageHeaderSize> ImageFileSource::CheckedSize(std::string_view bytes,
                                                           const std::string& name,
                                                           std::string* why) {
  std::string header_why;
  const std::optional<ImageHeaderSize> size = ReadImageHeaderSize(bytes, &header_why);
  if (!size) {
    *why = name + ": cannot read the image: " + header_why;
    return std::nullopt;
  }
  if (const std::string problem = ImageSizeProblem(size->width, size->height); !problem.empty()) {
    *why = name + ": image " + problem;
    return std::nullopt;
  }
  return size;
}

std::optional<ImageHeaderSize> ImageFileSource::HeaderSize(const std::string& path,
                                                           std::string* why) {
  InputFile file(path);
  std::string header;
  if (!file.ReadPrefix(kImageHeaderBytes, &header)) {
    *why = path + ": cannot read the image: " + file.error();
    return std::nullopt;
  }
  return CheckedSize(header, path, why);
}

cv::Mat ImageFileSource::DecodeGrey(const std::string& bytes, const std::string& name,
                                    std::string* why) {
  // The size its header declares, checked before OpenCV decodes (and allocates) anything:
  // a 1 MB PNG of 32000 x 32000 px took 3.6 GB (issue 42 point 2).
  const std::optional<ImageHeaderSize> size = CheckedSize(bytes, name, why);
  if (!size) return {};
  const std::vector<uint8_t> data(bytes.begin(), bytes.end());
  if (IsTruncatedJpeg(data)) {
    *why = name +
           ": truncated JPEG (no end-of-image marker FF D9: a partial copy or an "
           "interrupted write)";
    return {};
  }
  cv::Mat image;
  try {
    image = cv::imdecode(data, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image.release();  // OpenCV's refusal of a malformed file: said below, naming it
  }
  if (image.empty()) {
    *why = name + ": cannot read the image (not an image format OpenCV decodes, or damaged)";
    return {};
  }
  if (image.cols != size->width || image.rows != size->height) {
    *why = fmt::format("{}: decoded as {}x{} px, its header says {}x{}", name, image.cols,
                       image.rows, size->width, size->height);
    return {};
  }
  return ToGrey(image, name, why);
}

cv::Mat ImageFileSource::ReadGrey(const std::string& path, std::string* why) {
  InputFile file(path);
  std::string bytes;
  if (!file.ReadAll(kMaxImageFileBytes, &bytes)) {
    *why = path + ": cannot read the image: " + file.error();
    return {};
  }
  return DecodeGrey(bytes, path, why);
}

cv::Mat ImageFileSource::ToGrey(const cv::Mat& image, const std::string& name, std::string* why) {
  if (image.empty()) {
    *why = name + ": empty image (0 x 0 px)";
    return {};
  }
  if (image.depth() != CV_8U) {
    *why = fmt::format(
        "{}: {}-bit image; expected 8-bit (convert it, e.g. with a tool that scales to 8 bits)",
        name, 8 * image.elemSize1());
    return {};
  }
  cv::Mat grey;
  switch (image.channels()) {
    case 1:
      grey = image;
      break;
    case 3:
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
      break;
    default:
      *why = fmt::format("{}: {} channels; expected 1, 3 or 4", name, image.channels());
      return {};
  }
  return grey;
}

std::optional<Frame> ImageFileSource::Next(std::chrono::milliseconds /*timeout*/) {
  if (next_ >= files_.size()) return std::nullopt;
  const std::string& path = files_[next_];
  const int64_t sequence = static_cast<int64_t>(next_);
  ++next_;
  std::string why;
  cv::Mat grey = ReadGrey(path, &why);
  if (grey.empty()) {
    error_ = why;
    return std::nullopt;
  }
  error_.clear();
  Frame frame;
  frame.image = grey;
  frame.sequence = sequence;
  frame.origin = path;
  std::error_code ec;
  const auto written = fs::last_write_time(path, ec);
  if (!ec) {
    const auto system = std::chrono::file_clock::to_sys(written);
    frame.utime =
        std::chrono::duration_cast<std::chrono::microseconds>(system.time_since_epoch()).count();
  }
  return frame;
}

std::string ImageFileSource::Describe() const {
  std::string text = "files:";
  for (const std::string& path : paths_) text += " " + path;
  return text;
}

}  // namespace h4::cam
