// Board page layout; see board_layout.h. Tag bits come from tag_family.h (TagCells) and tag
// positions, ids and Kalibr's corner squares from board_model.h, as for the renderer, so
// print and render share one layout.
#include "firmware/board_print/board_layout.h"

#include <algorithm>
#include <cmath>

#include <apriltag/apriltag.h>
#include <fmt/format.h>

#include "common/board/board_model.h"
#include "firmware/detection/tag_family.h"

namespace h4::cam {
namespace {

constexpr double kMm = 0.001;
// Caption: two lines of text and the bar, below the pattern's bottom margin.
// Kept compact (12.5 mm) so that the 9x6 chessboard with a 5 mm margin fits A4 landscape.
constexpr double kTextSize = 3.0 * kMm;
constexpr double kLineGap = 4.5 * kMm;
constexpr double kBarHeight = 1.5 * kMm;
constexpr double kCaptionHeight = 2 * kLineGap + 1.0 * kMm + kBarHeight + 1.5 * kMm;
// The caption needs this much width (text and bar) even for a small board.
constexpr double kMinCaptionWidth = 150 * kMm;

std::string Mm(double metres) { return fmt::format("{:.1f} mm", metres / kMm); }

// Black cells of one tag, merged into runs along each row of cells.
void AddTag(const std::vector<bool>& cells, int width, double x0, double y0, double cell,
            std::vector<PrintRect>* black) {
  for (int row = 0; row < width; ++row) {
    int col = 0;
    while (col < width) {
      if (cells[static_cast<size_t>(row * width + col)]) {  // white
        ++col;
        continue;
      }
      const int start = col;
      while (col < width && !cells[static_cast<size_t>(row * width + col)]) ++col;
      black->push_back({x0 + start * cell, y0 + row * cell, (col - start) * cell, cell});
    }
  }
}

bool LayoutAprilGrid(const AprilGridSpec& grid, const BoardModel& model, double ox, double oy,
                     std::vector<PrintRect>* black, std::string* error) {
  const TagFamilyPtr family = CreateTagFamily(grid.tag_family);
  if (!family) {
    *error = "tag family '" + grid.tag_family + "' is not supported (tag36h11, tag25h9, tag16h5)";
    return false;
  }
  const int border_cells = grid.design().border_cells;
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const int id = model.TagIdAt(row, col);
      int width = 0;
      const std::vector<bool> cells = TagCells(*family, id, border_cells, &width);
      if (cells.empty()) {
        *error = fmt::format("tag id {} is beyond family {} ({} codes)", id, grid.tag_family,
                             family->ncodes);
        return false;
      }
      const auto origin = model.TagOrigin(row, col);
      AddTag(cells, width, ox + origin.x(), oy + origin.y(), grid.tag_size / width, black);
    }
  }
  const double side = model.corner_square_size();
  for (const Eigen::Vector2d& square : model.corner_squares()) {
    black->push_back({ox + square.x(), oy + square.y(), side, side});
  }
  return true;
}

void LayoutCheckerboard(const CheckerboardSpec& board, double ox, double oy,
                        std::vector<PrintRect>* black) {
  // (cols + 1) x (rows + 1) squares; square (i, j) spans x in [(i - 1) s, i s). The
  // top-left square is black, as board_pattern.h (the renderer) and OpenCV print it.
  for (int j = 0; j <= board.rows; ++j) {
    for (int i = 0; i <= board.cols; ++i) {
      if ((i + j) % 2 != 0) continue;
      black->push_back({ox + (i - 1) * board.col_spacing, oy + (j - 1) * board.row_spacing,
                        board.col_spacing, board.row_spacing});
    }
  }
}

}  // namespace

bool BoardPrintOptions::IsValid(std::string* why) const {
  if (!(margin >= 0.0 && margin <= 1.0)) {
    *why = fmt::format("margin must be in [0, 1] m, got {:f}", margin);
    return false;
  }
  return true;
}

std::string DescribeBoard(const BoardSpec& board) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    const std::string spacing = fmt::format("{:g}", grid->tag_spacing);
    return fmt::format(
        "aprilgrid {}x{} {} (ids {}-{}), tag {}, spacing {} (tagSpacing {}){}", grid->cols,
        grid->rows, grid->tag_family, grid->first_id, grid->first_id + grid->cols * grid->rows - 1,
        Mm(grid->tag_size), Mm(grid->tag_size * grid->tag_spacing), spacing,
        grid->layout == AprilGridLayout::kKalibr ? ", Kalibr layout (tag 0 bottom-left)" : "");
  }
  const auto& chess = std::get<CheckerboardSpec>(board);
  return fmt::format("checkerboard {}x{} inner corners, squares {} x {}", chess.cols, chess.rows,
                     Mm(chess.col_spacing), Mm(chess.row_spacing));
}

namespace {

constexpr double kA4Width = 210 * kMm, kA4Height = 297 * kMm;
constexpr double kA3Width = 297 * kMm, kA3Height = 420 * kMm;

const char* PaperName(PaperSize paper) { return paper == PaperSize::kA4 ? "A4" : "A3"; }

// The page (width, height) for content of `content_w` x `content_h`: portrait when it holds
// the content, else landscape; false with the reason when the paper asked for is too small.
bool PageSize(PaperSize paper, double content_w, double content_h, double* page_w,
              double* page_h, std::string* error) {
  *page_w = content_w;
  *page_h = content_h;
  if (paper == PaperSize::kFit) return true;
  if (paper == PaperSize::kSmallestIso) {
    for (const PaperSize iso : {PaperSize::kA4, PaperSize::kA3}) {
      std::string too_small;
      if (PageSize(iso, content_w, content_h, page_w, page_h, &too_small)) return true;
    }
    return true;  // beyond A3: the board's own size
  }
  const double short_side = paper == PaperSize::kA4 ? kA4Width : kA3Width;
  const double long_side = paper == PaperSize::kA4 ? kA4Height : kA3Height;
  if (content_w <= short_side && content_h <= long_side) {
    *page_w = short_side;
    *page_h = long_side;
    return true;
  }
  if (content_w <= long_side && content_h <= short_side) {
    *page_w = long_side;
    *page_h = short_side;
    return true;
  }
  *error = fmt::format(
      "the board with its margins and caption is {:.1f} x {:.1f} mm, more than {} ({:.0f} x "
      "{:.0f} mm) either way round: choose a larger paper, or fit",
      content_w / kMm, content_h / kMm, PaperName(paper), short_side / kMm, long_side / kMm);
  return false;
}

}  // namespace

bool LayoutBoard(const BoardSpec& board, const BoardPrintOptions& options, BoardLayout* layout,
                 std::string* error) {
  if (!options.IsValid(error)) return false;
  const BoardModel model(board);
  const double pattern_w = model.pattern_max().x() - model.pattern_min().x();
  const double pattern_h = model.pattern_max().y() - model.pattern_min().y();
  double content_w = pattern_w + 2 * options.margin;
  if (options.caption) content_w = std::max(content_w, kMinCaptionWidth + 2 * options.margin);
  const double content_h = pattern_h + 2 * options.margin + (options.caption ? kCaptionHeight : 0.0);
  BoardLayout out;
  if (!PageSize(options.paper, content_w, content_h, &out.width, &out.height, error)) return false;
  // The content centred on the page (a fitted page is the content: no shift).
  const double dx = (out.width - content_w) / 2, dy = (out.height - content_h) / 2;
  // Centre the pattern horizontally when the caption widened the content.
  out.pattern_x = dx + (content_w - pattern_w) / 2 - model.pattern_min().x();
  out.pattern_y = dy + options.margin - model.pattern_min().y();

  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    if (!LayoutAprilGrid(*grid, model, out.pattern_x, out.pattern_y, &out.black, error)) {
      return false;
    }
  } else {
    LayoutCheckerboard(std::get<CheckerboardSpec>(board), out.pattern_x, out.pattern_y, &out.black);
  }

  if (options.caption) {
    const double x = dx + std::max(options.margin, 2 * kMm);
    // Baselines one line gap apart below the bottom margin, then the bar.
    double y = dy + pattern_h + 2 * options.margin + kLineGap;
    out.texts.push_back({x, y, kTextSize, DescribeBoard(board)});
    y += kLineGap;
    // The two lengths the walkthrough's step 1 asks to measure.
    out.texts.push_back({x, y, kTextSize,
                         fmt::format("Print at 100% scale (no fit to page). Check: this bar is "
                                     "100 mm, the pattern {:.1f} x {:.1f} mm.",
                                     pattern_w / kMm, pattern_h / kMm)});
    out.scale_bar = {x, y + 1.0 * kMm, kScaleBarLength, kBarHeight};
  }
  *layout = std::move(out);
  return true;
}

}  // namespace h4::cam
