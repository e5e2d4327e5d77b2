// Image size limits and image file headers; see image_size.h.
#include "common/formats/image_size.h"

#include <cctype>
#include <cstdlib>

#include <fmt/format.h>

namespace h4 {
namespace {

uint32_t BigEndian(std::string_view b, size_t at, size_t n) {
  uint32_t value = 0;
  for (size_t i = 0; i < n; ++i) value = (value << 8) | static_cast<uint8_t>(b[at + i]);
  return value;
}

uint32_t LittleEndian(std::string_view b, size_t at, size_t n) {
  uint32_t value = 0;
  for (size_t i = n; i-- > 0;) value = (value << 8) | static_cast<uint8_t>(b[at + i]);
  return value;
}

bool StartsWith(std::string_view b, std::string_view prefix) {
  return b.substr(0, prefix.size()) == prefix;
}

std::optional<ImageHeaderSize> Fail(std::string* why, const std::string& what) {
  *why = what;
  return std::nullopt;
}

// PNG: the signature, then the IHDR chunk (length 13) with width and height, big-endian.
std::optional<ImageHeaderSize> PngSize(std::string_view b, std::string* why) {
  if (b.size() < 24 || b.substr(12, 4) != "IHDR") return Fail(why, "PNG header cut short");
  return ImageHeaderSize{BigEndian(b, 16, 4), BigEndian(b, 20, 4)};
}

// JPEG: the segments after SOI up to the first start-of-frame (SOF0..SOF15 but DHT C4, JPG
// C8, DAC CC), whose payload is precision, height, width.
std::optional<ImageHeaderSize> JpegSize(std::string_view b, std::string* why) {
  size_t at = 2;
  while (at + 4 <= b.size()) {
    if (static_cast<uint8_t>(b[at]) != 0xFF) {
      return Fail(why, "JPEG header: no marker where one belongs");
    }
    const auto marker = static_cast<uint8_t>(b[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // no length
      at += 2;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) break;  // end of image, start of scan: no frame
    const size_t length = BigEndian(b, at + 2, 2);
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
                       marker != 0xCC;
    if (frame) {
      if (at + 9 > b.size()) break;
      return ImageHeaderSize{BigEndian(b, at + 7, 2), BigEndian(b, at + 5, 2)};
    }
    if (length < 2) return Fail(why, "JPEG header: a segment shorter than its length field");
    at += 2 + length;
  }
  return Fail(why, "JPEG header cut short (no frame header)");
}

// BMP: the file header (14 bytes), then the DIB header: 12 bytes (OS/2, 16-bit sizes) or
// more (32-bit signed sizes; a negative height is a top-down image).
std::optional<ImageHeaderSize> BmpSize(std::string_view b, std::string* why) {
  if (b.size() < 26) return Fail(why, "BMP header cut short");
  if (LittleEndian(b, 14, 4) == 12) {
    return ImageHeaderSize{LittleEndian(b, 18, 2), LittleEndian(b, 20, 2)};
  }
  const auto width = static_cast<int32_t>(LittleEndian(b, 18, 4));
  const auto height = static_cast<int32_t>(LittleEndian(b, 22, 4));
  return ImageHeaderSize{width, height < 0 ? -int64_t{height} : int64_t{height}};
}

// PNM (P1..P6): "P<n>", then width and height as decimal numbers among whitespace and
// '#' comments.
std::optional<ImageHeaderSize> PnmSize(std::string_view b, std::string* why) {
  size_t at = 2;
  int64_t numbers[2] = {0, 0};
  for (int64_t& number : numbers) {
    while (at < b.size() && (std::isspace(static_cast<unsigned char>(b[at])) || b[at] == '#')) {
      if (b[at] == '#') {
        while (at < b.size() && b[at] != '\n') ++at;
      } else {
        ++at;
      }
    }
    size_t digits = 0;
    number = 0;
    while (at < b.size() && std::isdigit(static_cast<unsigned char>(b[at])) && digits < 10) {
      number = number * 10 + (b[at] - '0');
      ++at;
      ++digits;
    }
    if (digits == 0) return Fail(why, "PNM header: expected the width and height");
  }
  return ImageHeaderSize{numbers[0], numbers[1]};
}

// TIFF: byte order "II" or "MM", 42, the first IFD's offset; in that IFD the tags
// ImageWidth (256) and ImageLength (257), SHORT or LONG.
std::optional<ImageHeaderSize> TiffSize(std::string_view b, std::string* why) {
  const bool little = b[0] == 'I';
  const auto read = [&](size_t at, size_t n) {
    return little ? LittleEndian(b, at, n) : BigEndian(b, at, n);
  };
  if (b.size() < 8) return Fail(why, "TIFF header cut short");
  const size_t ifd = read(4, 4);
  if (ifd + 2 > b.size()) return Fail(why, "TIFF header: the first directory is past the header");
  const size_t entries = read(ifd, 2);
  int64_t size[2] = {-1, -1};
  for (size_t e = 0; e < entries && ifd + 2 + 12 * (e + 1) <= b.size(); ++e) {
    const size_t at = ifd + 2 + 12 * e;
    const uint32_t tag = read(at, 2);
    const uint32_t type = read(at + 2, 2);
    if (tag != 256 && tag != 257) continue;
    const uint32_t value = type == 3 ? read(at + 8, 2) : type == 4 ? read(at + 8, 4) : 0;
    size[tag - 256] = value;
  }
  if (size[0] < 0 || size[1] < 0) return Fail(why, "TIFF header: no image width and length");
  return ImageHeaderSize{size[0], size[1]};
}

}  // namespace

std::string ImageSizeLimits() {
  return fmt::format("{}..{} px a side and at most {} px in all", kMinImageSide_px,
                     kMaxImageSide_px, kMaxImagePixels);
}

std::string ImageSizeProblem(int64_t width, int64_t height) {
  const bool sides_ok = width >= kMinImageSide_px && height >= kMinImageSide_px &&
                        width <= kMaxImageSide_px && height <= kMaxImageSide_px;
  // Both sides within kMaxImageSide_px before the product: it cannot overflow.
  if (sides_ok && width * height <= kMaxImagePixels) return "";
  return fmt::format("{}x{} px: expected {}", width, height, ImageSizeLimits());
}

std::optional<ImageHeaderSize> ReadImageHeaderSize(std::string_view b, std::string* why) {
  if (StartsWith(b, "\x89PNG\r\n\x1a\n")) return PngSize(b, why);
  if (StartsWith(b, "\xFF\xD8")) return JpegSize(b, why);
  if (StartsWith(b, "BM")) return BmpSize(b, why);
  if (b.size() >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '6') return PnmSize(b, why);
  if (StartsWith(b, std::string_view("II*\0", 4)) || StartsWith(b, std::string_view("MM\0*", 4))) {
    return TiffSize(b, why);
  }
  return Fail(why, "not an image format h4cam reads (PNG, JPEG, BMP, PNM, TIFF)");
}

}  // namespace h4
