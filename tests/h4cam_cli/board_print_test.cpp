// Printable boards: the SVG/PDF page size in mm matches the board, the check bar is 100 mm,
// a PNG raster at a dpi is detected back (OpenCV chessboard, AprilTag grids of both
// layouts) at the expected pixel spacing, a Kalibr board is cell for cell what
// kalibr_create_target_pdf draws, the PNG carries its dpi, and the committed boards/
// printables are what make-board writes today.
#include "firmware/board_print/board_print.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/board/board_model.h"
#include "common/formats/board_yaml.h"
#include "firmware/board_print/board_layout.h"
#include "firmware/cli/make_board_command.h"
#include "firmware/detection/apriltag_detector.h"

namespace h4::cam {
namespace {

namespace fs = std::filesystem;

BoardLayout Layout(const BoardSpec& board, double margin, bool caption = true) {
  BoardPrintOptions options;
  options.margin = margin;
  options.caption = caption;
  BoardLayout layout;
  std::string error;
  EXPECT_TRUE(LayoutBoard(board, options, &layout, &error)) << error;
  return layout;
}

// h4cam's legacy design with the geometry of boards/aprilgrid_6x6_30mm.yaml.
AprilGridSpec LegacyGrid() {
  AprilGridSpec grid;
  grid.layout = AprilGridLayout::kH4Legacy;
  return grid;
}

double Attribute(const std::string& svg, const std::string& name) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(svg, m, std::regex("<svg[^>]* " + name + "=\"([0-9.]+)mm\"")));
  return m.empty() ? 0 : std::stod(m[1]);
}

std::string ReadFile(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(BoardPrint, SvgPageIsTheAprilGridPlusItsMarginsInMillimetres) {
  // 6 tags of 30 mm and 5 gaps of 7.5 mm = 217.5 mm, plus 2 x 10 mm of margin.
  const std::string svg = BoardSvg(Layout(LegacyGrid(), 0.01, false));
  EXPECT_DOUBLE_EQ(Attribute(svg, "width"), 237.5);
  EXPECT_DOUBLE_EQ(Attribute(svg, "height"), 237.5);
  EXPECT_NE(svg.find("viewBox=\"0 0 237.5 237.5\""), std::string::npos);
  // Tag 0's black border starts at the margin: its top row is one full black run.
  EXPECT_NE(svg.find("<rect x=\"10\" y=\"10\" width=\"30\" height=\"3.75\"/>"), std::string::npos);
  // The last tag (row 5, column 5): its bottom border row ends at 10 + 217.5 = 227.5 mm.
  EXPECT_NE(svg.find("<rect x=\"197.5\" y=\"223.75\" width=\"30\" height=\"3.75\"/>"),
            std::string::npos);
}

TEST(BoardPrint, SvgOfTheChessboardHasTenBySevenSquaresAndTheCaption) {
  const CheckerboardSpec chess;  // 9 x 6 inner corners, 25 mm
  const BoardLayout layout = Layout(chess, 0.005);
  const std::string svg = BoardSvg(layout);
  EXPECT_DOUBLE_EQ(Attribute(svg, "width"), 260.0);  // 10 squares + 2 x 5 mm
  EXPECT_GT(Attribute(svg, "height"), 185.0);        // 7 squares + 2 x 5 mm + caption
  EXPECT_LE(Attribute(svg, "height"), 200.0);        // fits A4 landscape (210 mm)
  EXPECT_EQ(layout.black.size(), 35u);               // half of the 10 x 7 squares
  EXPECT_NE(svg.find("checkerboard 9x6 inner corners, squares 25.0 mm x 25.0 mm"),
            std::string::npos);
  EXPECT_NE(svg.find("<rect id=\"scale_bar_100mm\" x=\"5\" y=\""), std::string::npos);
  EXPECT_NE(svg.find("width=\"100\" height=\"1.5\"/>"), std::string::npos);
}

TEST(BoardPrint, CaptionStatesTheAprilGridDimensions) {
  EXPECT_EQ(DescribeBoard(LegacyGrid()),
            "aprilgrid 6x6 tag36h11 (ids 0-35), tag 30.0 mm, spacing 7.5 mm (tagSpacing 0.25)");
  EXPECT_EQ(DescribeBoard(AprilGridSpec{}),
            "aprilgrid 6x6 tag36h11 (ids 0-35), tag 30.0 mm, spacing 7.5 mm (tagSpacing 0.25), "
            "Kalibr layout (tag 0 bottom-left)");
}

// Issue 43 point 8: the page a printer takes at 100 % (A3 for the 217.5 mm grid, the board
// centred), and the caption names the pattern's size, which step 1 asks to measure.
TEST(BoardPrint, TheGridIsCentredOnAnA3PageWhoseCaptionGivesThePatternSize) {
  BoardPrintOptions options;
  options.paper = PaperSize::kSmallestIso;
  BoardLayout layout;
  std::string error;
  ASSERT_TRUE(LayoutBoard(LegacyGrid(), options, &layout, &error)) << error;
  EXPECT_DOUBLE_EQ(layout.width, 0.297);
  EXPECT_DOUBLE_EQ(layout.height, 0.420);
  // Centred across: the pattern's left edge as far from the page's as its right edge.
  EXPECT_NEAR(layout.pattern_x, (0.297 - 0.2175) / 2, 1e-12);
  ASSERT_EQ(layout.texts.size(), 2u);
  EXPECT_NE(layout.texts[1].text.find("the pattern 217.5 x 217.5 mm"), std::string::npos)
      << layout.texts[1].text;
  // A4 cannot hold it either way round: said, not shrunk.
  options.paper = PaperSize::kA4;
  EXPECT_FALSE(LayoutBoard(LegacyGrid(), options, &layout, &error));
  EXPECT_NE(error.find("more than A4 (210 x 297 mm)"), std::string::npos) << error;
  // The chessboard (260 mm wide) takes A4 landscape.
  options.paper = PaperSize::kSmallestIso;
  options.margin = 0.005;
  ASSERT_TRUE(LayoutBoard(CheckerboardSpec{}, options, &layout, &error)) << error;
  EXPECT_DOUBLE_EQ(layout.width, 0.297);
  EXPECT_DOUBLE_EQ(layout.height, 0.210);
}

TEST(BoardPrint, PngOfTheChessboardIsDetectedAtTheExpectedPixelSpacing) {
  const double dpi = 100;
  const double px_per_m = dpi / 0.0254;
  const BoardLayout layout = Layout(CheckerboardSpec{}, 0.01);
  const std::string png = BoardPng(layout, dpi);
  const cv::Mat page =
      cv::imdecode(std::vector<uint8_t>(png.begin(), png.end()), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(page.empty());
  EXPECT_EQ(page.cols, static_cast<int>(std::lround(layout.width * px_per_m)));
  std::vector<cv::Point2f> corners;
  ASSERT_TRUE(cv::findChessboardCorners(page, cv::Size(9, 6), corners));
  cv::cornerSubPix(page, corners, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 1e-4));
  // Inner-corner pitch: 25 mm at 100 dpi = 98.43 px; edges are rounded to whole pixels, so
  // neighbours differ by 98 or 99 px, and the 8-square span is exact to half a pixel.
  const double pitch = 0.025 * px_per_m;
  const auto& first = corners.front();
  const auto& last_in_row = corners[8];
  EXPECT_NEAR(std::abs(last_in_row.x - first.x), 8 * pitch, 0.6);
  EXPECT_NEAR(std::abs(corners[9].y - first.y), pitch, 0.6);
  // The first inner corner (either end: OpenCV may start at the opposite corner) is where
  // the layout put frame T's origin; OpenCV's pixel centres are at integer coordinates.
  const cv::Point2f origin(static_cast<float>(layout.pattern_x * px_per_m - 0.5),
                           static_cast<float>(layout.pattern_y * px_per_m - 0.5));
  const cv::Point2f far_corner(static_cast<float>(origin.x + 8 * pitch),
                               static_cast<float>(origin.y + 5 * pitch));
  const double d = std::min(cv::norm(first - origin), cv::norm(first - far_corner));
  EXPECT_LT(d, 0.6) << first;
}

// Prints `grid` at 100 dpi, detects it back and checks every tag's top-left corner.
void ExpectPngDetectedWithEveryIdInPlace(const AprilGridSpec& grid) {
  const double dpi = 100;
  const double px_per_m = dpi / 0.0254;
  const BoardLayout layout = Layout(grid, 0.01);
  const std::string png = BoardPng(layout, dpi);
  const cv::Mat page =
      cv::imdecode(std::vector<uint8_t>(png.begin(), png.end()), cv::IMREAD_GRAYSCALE);
  AprilTagOptions options;
  options.border_cells = grid.design().border_cells;
  options.open_contacts_px = grid.design().corner_squares ? 1 : 0;
  AprilTagDetector detector(options);
  ASSERT_TRUE(detector.ok()) << detector.error();
  const auto tags = detector.Detect(page);
  ASSERT_EQ(tags.size(), 36u);
  const BoardModel model(grid);
  std::vector<bool> seen(36, false);
  for (const auto& tag : tags) {
    ASSERT_GE(tag.id, 0);
    ASSERT_LT(tag.id, 36);
    seen[static_cast<size_t>(tag.id)] = true;
    // Corner k = 3 is the tag's outer top-left corner (board_model.h).
    const Eigen::Vector3d p = *model.Corner(model.TagCornerId(tag.id, 3));
    const Eigen::Vector2d expected((layout.pattern_x + p.x()) * px_per_m - 0.5,
                                   (layout.pattern_y + p.y()) * px_per_m - 0.5);
    // Opening the corner contacts moves the corners in by up to sqrt(2) px.
    EXPECT_LT((tag.corners_px[3] - expected).norm(), grid.design().corner_squares ? 2.5 : 1.0)
        << "tag " << tag.id;
  }
  for (int id = 0; id < 36; ++id) EXPECT_TRUE(seen[static_cast<size_t>(id)]) << id;
}

TEST(BoardPrint, PngOfTheLegacyAprilGridIsDetectedWithEveryIdInPlace) {
  ExpectPngDetectedWithEveryIdInPlace(LegacyGrid());
}

TEST(BoardPrint, PngOfTheKalibrAprilGridIsDetectedWithEveryIdInPlace) {
  AprilGridSpec grid;  // Kalibr's layout, 30 mm tags: 10 cells of 11.8 px at 100 dpi
  grid.tag_spacing = 0.3;
  ExpectPngDetectedWithEveryIdInPlace(grid);
}

// kalibr_create_target_pdf (aslam_offline_calibration/kalibr/python), re-stated: page
// coordinates with y up, tag i at ((i % nx) pitch, (i / nx) pitch), a black border of
// borderBits = 2 cells of size tagSize / (6 + 4), the code drawn MSB-first from its
// top-left data cell after np.rot90(codeMatrix, 2), and a tagSpacing * tagSize square at
// each of the tag's four outer corners. Returns whether the point (x, y_up) is black.
bool KalibrBlackAt(const std::vector<uint64_t>& codes, int nx, int ny, double size, double spacing,
                   double x, double y_up) {
  const double pitch = (1 + spacing) * size, bit = size / 10, square = spacing * size;
  for (int i = 0; i < nx * ny; ++i) {
    const double x0 = (i % nx) * pitch, y0 = (i / nx) * pitch;
    const auto in = [&](double rx, double ry, double w, double h) {
      return x >= rx && x < rx + w && y_up >= ry && y_up < ry + h;
    };
    for (const auto& [sx, sy] : {std::pair{x0 - square, y0 - square},
                                 {x0 + size, y0 - square},
                                 {x0 + size, y0 + size},
                                 {x0 - square, y0 + size}}) {
      if (in(sx, sy, square, square)) return true;
    }
    if (!in(x0, y0, size, size)) continue;
    if (!in(x0 + 2 * bit, y0 + 2 * bit, 6 * bit, 6 * bit)) return true;  // border
    for (int r = 0; r < 6; ++r) {                     // rows of the rotated matrix, from the top
      for (int c = 0; c < 6; ++c) {                   // columns
        const int bit_index = 6 * (5 - r) + (5 - c);  // rot90 twice
        const bool black = !(codes[static_cast<size_t>(i)] & (uint64_t{1} << bit_index));
        if (black && in(x0 + (c + 2) * bit, y0 + (1 + 6 - r) * bit, bit, bit)) return true;
      }
    }
  }
  return false;
}

TEST(BoardPrint, KalibrLayoutIsCellForCellWhatKalibrCreateTargetPdfDraws) {
  // The first four codes of Kalibr's t36h11 table (kalibr_create_target_pdf).
  const std::vector<uint64_t> codes = {0xd5d628584, 0xd97f18b49, 0xdd280910e, 0xe479e9c98};
  AprilGridSpec grid;  // Kalibr's layout
  grid.cols = 2;
  grid.rows = 2;
  grid.tag_size = 0.1;
  grid.tag_spacing = 0.3;  // pitch 13 cells of 10 mm, squares 3 cells
  const BoardLayout layout = Layout(grid, 0.0, false);
  const double cell = 0.01, height = 2 * 0.1 + 0.03;  // tag grid height H
  int black = 0, checked = 0;
  // Every cell centre of the pattern (squares included) and one cell of margin around it.
  for (int j = -4; j < 27; ++j) {
    for (int i = -4; i < 27; ++i) {
      const double x = (i + 0.5) * cell, y = (j + 0.5) * cell;  // frame T, y down
      bool ours = false;
      for (const PrintRect& r : layout.black) {
        const double px = layout.pattern_x + x, py = layout.pattern_y + y;
        ours |= px >= r.x && px < r.x + r.w && py >= r.y && py < r.y + r.h;
      }
      const bool kalibr = KalibrBlackAt(codes, 2, 2, 0.1, 0.3, x, height - y);
      EXPECT_EQ(ours, kalibr) << "cell (" << i << ", " << j << ") of T";
      black += ours;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 31 * 31);
  EXPECT_GT(black, 4 * 64 + 9 * 9);  // borders and squares at least
}

TEST(BoardPrint, PngCarriesItsDpiInAPhysChunk) {
  const std::string png = BoardPng(Layout(CheckerboardSpec{}, 0.01), 300);
  ASSERT_GT(png.size(), 54u);
  // Right after the signature (8) and IHDR (25): length 9, "pHYs", 11811 px/m twice,
  // unit 1 (metre), CRC 0x78a53f76 (computed with Python's zlib.crc32).
  const std::string expected(
      "\x00\x00\x00\x09pHYs\x00\x00\x2e\x23\x00\x00\x2e\x23\x01"
      "\x78\xa5\x3f\x76",
      21);
  EXPECT_EQ(png.substr(33, 21), expected);
}

TEST(BoardPrint, PdfIsOnePageOfTheBoardSizeWithAValidCrossReferenceTable) {
  const BoardLayout layout = Layout(AprilGridSpec{}, 0.01);
  const std::string pdf = BoardPdf(layout);
  ASSERT_EQ(pdf.rfind("%PDF-1.4\n", 0), 0u);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(pdf, m, std::regex("/MediaBox \\[0 0 ([0-9.]+) ([0-9.]+)\\]")));
  EXPECT_NEAR(std::stod(m[1]), layout.width / 0.0254 * 72, 1e-3);
  EXPECT_NEAR(std::stod(m[2]), layout.height / 0.0254 * 72, 1e-3);
  ASSERT_TRUE(std::regex_search(pdf, m, std::regex("startxref\n([0-9]+)\n%%EOF\n$")));
  const size_t xref = std::stoul(m[1]);
  ASSERT_EQ(pdf.compare(xref, 5, "xref\n"), 0);
  // Five objects, each entry 20 bytes, each offset pointing at "<n> 0 obj".
  for (int n = 1; n <= 5; ++n) {
    const size_t entry = xref + std::string("xref\n0 6\n").size() + 20 * static_cast<size_t>(n);
    const size_t offset = std::stoul(pdf.substr(entry, 10));
    const std::string header = fmt::format("{} 0 obj\n", n);
    EXPECT_EQ(pdf.compare(offset, header.size(), header), 0) << n;
  }
  ASSERT_TRUE(std::regex_search(pdf, m, std::regex("/Length ([0-9]+) >>\nstream\n")));
  const size_t stream_start = static_cast<size_t>(m.position(0) + m.length(0));
  EXPECT_EQ(pdf.compare(stream_start + std::stoul(m[1]), 9, "endstream"), 0);
  EXPECT_NE(pdf.find("this bar is 100 mm"), std::string::npos);
}

TEST(BoardPrint, UnknownExtensionAndUnsupportedFamilyAreErrors) {
  std::string error;
  EXPECT_FALSE(WriteBoardFile("/tmp/board.jpg", Layout(CheckerboardSpec{}, 0.01), 300, &error));
  EXPECT_NE(error.find("/tmp/board.jpg: unknown extension"), std::string::npos) << error;
  AprilGridSpec grid;
  grid.tag_family = "tagStandard41h12";
  BoardLayout layout;
  EXPECT_FALSE(LayoutBoard(grid, {}, &layout, &error));
  EXPECT_NE(error.find("tagStandard41h12"), std::string::npos);
  grid = LegacyGrid();
  grid.first_id = 570;  // tag36h11 has 587 codes: ids 570..605 run past the end
  EXPECT_FALSE(LayoutBoard(grid, {}, &layout, &error));
  EXPECT_NE(error.find("tag id 587 is beyond family tag36h11"), std::string::npos) << error;
}

// issue 27 point 8: a PNG had no pixel limit: a board of 0.5 m tags took 2.1 GB, tagSize 10
// asked OpenCV for 838 GB. The page is sized before anything is allocated.
TEST(BoardPrint, APngPageBeyondThePixelLimitIsRefusedBeforeAllocating) {
  const fs::path tmp = fs::temp_directory_path() / "h4_board_print_limit.png";
  AprilGridSpec huge = LegacyGrid();
  huge.tag_size = 10.0;
  BoardLayout layout;
  std::string error;
  ASSERT_TRUE(LayoutBoard(huge, {}, &layout, &error)) << error;
  EXPECT_FALSE(WriteBoardFile(tmp.string(), layout, 300, &error));
  EXPECT_NE(error.find("Mpx a PNG may have"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_TRUE(WriteBoardFile(tmp.string(), Layout(CheckerboardSpec{}, 0.01), 300, &error)) << error;
  fs::remove(tmp);
}

// boards/README.md gives the commands that made the committed printables; this checks
// they are still what make-board writes.
TEST(BoardPrint, CommittedPrintablesAreUpToDate) {
  const fs::path boards = fs::path(H4_SOURCE_DIR) / "boards";
  const fs::path tmp = fs::temp_directory_path() / "h4_board_print_test";
  fs::create_directories(tmp);
  struct Printable {
    const char* name;
    double margin;
  };
  for (const auto& [name, margin] :
       {Printable{"aprilgrid_6x6_30mm", 0.01}, Printable{"checkerboard_9x6_25mm", 0.005},
        Printable{"kalibr_aprilgrid_6x6_30mm", 0.01},
        Printable{"kalibr_aprilgrid_6x6_88mm", 0.01}}) {
    for (const char* ext : {".svg", ".pdf"}) {
      const fs::path committed = boards / (std::string(name) + ext);
      if (!fs::exists(committed)) {
        ADD_FAILURE() << committed << " is missing";
        continue;
      }
      MakeBoardArgs args;
      args.board_path = (boards / (std::string(name) + ".yaml")).string();
      args.out_path = (tmp / (std::string(name) + ext)).string();
      args.margin = margin;
      std::ostringstream log;
      RunMakeBoard(args, log);
      EXPECT_EQ(ReadFile(args.out_path), ReadFile(committed))
          << committed << " differs from make-board's output: regenerate it (boards/README.md)";
    }
  }
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace h4::cam
