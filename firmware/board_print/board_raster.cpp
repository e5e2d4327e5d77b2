// PNG writer of a board page and the file dispatcher; see board_print.h.
#include <array>
#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "firmware/board_print/board_print.h"

namespace h4::cam {
namespace {

constexpr double kMetresPerInch = 0.0254;

uint32_t Crc32(const uint8_t* data, size_t size) {
  // PNG's CRC-32 (ISO 3309, reflected polynomial 0xEDB88320), bit by bit: 17 bytes only.
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

void PutBigEndian(uint32_t value, std::string* out) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<char>(value >> shift));
}

// pHYs chunk: pixels per metre on both axes, unit 1 (metre).
std::string PhysChunk(double dpi) {
  const auto ppm = static_cast<uint32_t>(std::lround(dpi / kMetresPerInch));
  std::string body = "pHYs";
  PutBigEndian(ppm, &body);
  PutBigEndian(ppm, &body);
  body.push_back('\x01');
  std::string chunk;
  PutBigEndian(9, &chunk);
  chunk += body;
  PutBigEndian(Crc32(reinterpret_cast<const uint8_t*>(body.data()), body.size()), &chunk);
  return chunk;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == suffix;
}

}  // namespace

cv::Mat BoardRaster(const BoardLayout& layout, double dpi) {
  const double px_per_m = dpi / kMetresPerInch;
  const auto px = [px_per_m](double metres) {
    return static_cast<int>(std::lround(metres * px_per_m));
  };
  cv::Mat page(px(layout.height), px(layout.width), CV_8UC1, cv::Scalar(255));
  auto fill = [&](const PrintRect& r) {
    // Pixel i covers [i, i + 1) / px_per_m: edges rounded to the nearest pixel boundary.
    const cv::Rect box(cv::Point(px(r.x), px(r.y)), cv::Point(px(r.x + r.w), px(r.y + r.h)));
    page(box & cv::Rect(0, 0, page.cols, page.rows)).setTo(0);
  };
  for (const auto& r : layout.black) fill(r);
  if (layout.scale_bar.w > 0) fill(layout.scale_bar);
  for (const auto& t : layout.texts) {
    // Hershey simplex: cap height about 22 px at scale 1; the em is about 1.4 cap heights.
    const double size_px = t.size * px_per_m;
    const double scale = size_px / 1.4 / 22.0;
    const int thickness = std::max(1, static_cast<int>(std::lround(size_px / 14.0)));
    cv::putText(page, t.text, cv::Point(px(t.x), px(t.y)), cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar(0), thickness, cv::LINE_AA);
  }
  return page;
}

std::string BoardPng(const BoardLayout& layout, double dpi) {
  std::vector<uint8_t> bytes;
  cv::imencode(".png", BoardRaster(layout, dpi), bytes);
  std::string png(bytes.begin(), bytes.end());
  // The 8-byte signature and the IHDR chunk (4 + 4 + 13 + 4 bytes) come first; pHYs must
  // precede the image data, so it goes right after IHDR.
  constexpr size_t kAfterIhdr = 8 + 25;
  png.insert(kAfterIhdr, PhysChunk(dpi));
  return png;
}

bool WriteBoardFile(const std::string& path, const BoardLayout& layout, double dpi,
                    std::string* error) {
  std::string bytes;
  if (EndsWith(path, ".svg")) {
    bytes = BoardSvg(layout);
  } else if (EndsWith(path, ".pdf")) {
    bytes = BoardPdf(layout);
  } else if (EndsWith(path, ".png")) {
    if (!(dpi >= 50 && dpi <= 2400)) {
      *error = fmt::format("{}: dpi must be in [50, 2400], got {:f}", path, dpi);
      return false;
    }
    // Sized in floating point before anything is allocated: a board of 0.5 m tags took
    // 2.1 GB, tagSize 10 asked OpenCV for 838 GB (and a side past INT_MAX px overflows).
    const double px_per_m = dpi / kMetresPerInch;
    const double pixels =
        std::round(layout.width * px_per_m) * std::round(layout.height * px_per_m);
    if (!(pixels <= kMaxBoardPngPixels)) {
      *error = fmt::format(
          "{}: the page is {} Mpx at {} dpi, more than the {} Mpx a PNG may have; lower --dpi or "
          "write .svg or .pdf (vector, any size)",
          path, std::llround(pixels / 1e6), std::lround(dpi),
          std::llround(kMaxBoardPngPixels / 1e6));
      return false;
    }
    bytes = BoardPng(layout, dpi);
  } else {
    *error = path + ": unknown extension, expected .svg, .pdf or .png";
    return false;
  }
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!file) {
    *error = path + ": cannot write the file";
    return false;
  }
  return true;
}

}  // namespace h4::cam
