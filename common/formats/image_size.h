// The image sizes h4cam works with, and the size an image file's header declares, read before
// anything is decoded (common/formats/README.md#image-sizes). One set of limits for the camera
// file, the service's stream, every image reader and the detector's entry.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace h4 {

/// The smallest image side: 32 px. libapriltag's quad search runs on the image decimated by
/// 2 and crashes on an image 4 px high or less (issue 42 point 1); a tag of the smallest
/// family (8 cells with its border) needs 2 px a cell after that decimation (8 x 2 x 2 =
/// 32 px), and a board has at least 3 tags or 3 x 3 inner corners.
constexpr int kMinImageSide_px = 32;
/// The largest image a camera file, a stream or an image file may have: 16384 px a side and
/// 16.8 Mpx (2^24) in all, 1.4 times the 12 Mpx of the largest Raspberry Pi camera module.
/// What is sized from the camera grows with its area (measured: `h4cam render` of one
/// 64 Mpx frame took 143 s and 2.7 GB, of one 16.8 Mpx frame 39 s and 0.7 GB); a 20000 x
/// 20000 file is refused before anything is allocated.
constexpr int kMaxImageSide_px = 16384;
constexpr int64_t kMaxImagePixels = int64_t{1} << 24;
/// The largest image file read: kMaxImagePixels at 8 bytes a pixel (16-bit RGBA, stored
/// uncompressed), 128 MiB.
constexpr size_t kMaxImageFileBytes = static_cast<size_t>(kMaxImagePixels) * 8;

/// Empty when a width x height px image is within the limits above, else why:
/// "64x3 px: expected 32..16384 px a side and at most 16777216 px in all".
std::string ImageSizeProblem(int64_t width, int64_t height);
/// "32..16384 px a side and at most 16777216 px in all", for messages.
std::string ImageSizeLimits();

struct ImageHeaderSize {
  int64_t width = 0;
  int64_t height = 0;
};

/// How many bytes of a file ReadImageHeaderSize may need: a JPEG's size sits after its
/// APPn segments (Exif, ICC profile), each up to 64 KiB.
constexpr size_t kImageHeaderBytes = size_t{1} << 20;

/// The size declared by the header of a PNG, JPEG, BMP, PNM (P1..P6) or TIFF file, from its
/// first bytes (the whole file, or at least its first kImageHeaderBytes); nullopt with why
/// for another format or a header cut short.
std::optional<ImageHeaderSize> ReadImageHeaderSize(std::string_view bytes, std::string* why);

}  // namespace h4
