// Writers of a board page (board_layout.h): SVG (text, size in mm), PDF (one page of vector
// rectangles, written by hand) and PNG (OpenCV raster at a given dpi, with the dpi stored
// in the file's pHYs chunk so printing software keeps the scale).
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "firmware/board_print/board_layout.h"

namespace h4::cam {

/// SVG document: width/height in mm, viewBox in mm, one <rect> per black rectangle.
std::string BoardSvg(const BoardLayout& layout);

/// PDF document (PDF 1.4, one page the size of the layout, Helvetica captions).
std::string BoardPdf(const BoardLayout& layout);

/// CV_8UC1 raster of the page at `dpi` dots per inch (black 0, white 255). Each rectangle
/// edge is rounded to the nearest pixel boundary, so no edge moves by more than half a pixel.
cv::Mat BoardRaster(const BoardLayout& layout, double dpi);

/// PNG bytes of BoardRaster with a pHYs chunk for `dpi`.
std::string BoardPng(const BoardLayout& layout, double dpi);

/// The largest PNG page WriteBoardFile rasterises, px (256 MB at a byte a pixel: an A0
/// page at 400 dpi).
inline constexpr double kMaxBoardPngPixels = 256.0 * 1024 * 1024;

/// Writes the format chosen by the extension of `path` (.svg, .pdf, .png); false with
/// `error` naming the path for an unknown extension, a PNG of more than kMaxBoardPngPixels
/// or a failed write.
bool WriteBoardFile(const std::string& path, const BoardLayout& layout, double dpi,
                    std::string* error);

}  // namespace h4::cam
