// Calibration board descriptions (board YAML, common/formats/README.md#board-yaml---board): an
// AprilTag grid with Kalibr's keys, or an OpenCV chessboard. Board frame T: origin at the
// outer top-left corner of the top-left tag as printed (the first inner corner of a
// chessboard), x right along a row, y down a column, z into the board (away from the print).
#pragma once

#include <optional>
#include <string>
#include <variant>

namespace h4 {

/// The fewest board corners a measurement uses (a pose from fewer is unreliable: h4cam's
/// detector reports such a view as partial, DetectorOptions::min_corners): the board reader
/// refuses a board with fewer corners in all, which h4cam could never measure.
inline constexpr int kMinBoardCorners = 12;
/// OpenCV's chessboard detectors need more than 2 inner corners per side (they assert so).
inline constexpr int kMinChessboardCornersPerSide = 3;

/// How the tags of an AprilTag grid are drawn and numbered.
enum class AprilGridLayout {
  /// As kalibr_create_target_pdf prints it (and a plain Kalibr YAML means): tags with a
  /// 2-cell black border, a black square of side tagSpacing * tagSize at every tag corner
  /// (in the gaps, so every tag corner is an X-corner), ids from the bottom-left tag of the
  /// page running right, then up.
  kKalibr,
  /// h4cam's earlier design (YAML `h4camLayout: legacy`): libapriltag's tags with a 1-cell
  /// black border, no corner squares, ids from the top-left tag running right, then down.
  kH4Legacy,
};

/// The drawing rules a layout stands for.
struct AprilGridDesign {
  int border_cells = 2;         ///< black border width, in tag cells (bits)
  bool corner_squares = true;   ///< black squares in the gaps at every tag corner
  bool ids_from_bottom = true;  ///< firstId is the bottom-left tag (else the top-left one)
};

inline AprilGridDesign DesignOf(AprilGridLayout layout) {
  if (layout == AprilGridLayout::kH4Legacy) {
    return {.border_cells = 1, .corner_squares = false, .ids_from_bottom = false};
  }
  return {.border_cells = 2, .corner_squares = true, .ids_from_bottom = true};
}

struct AprilGridSpec {
  std::string tag_family = "tag36h11";
  int cols = 6;               ///< tagCols
  int rows = 6;               ///< tagRows
  double tag_size = 0.03;     ///< tagSize: outer edge of the black border, m
  double tag_spacing = 0.25;  ///< tagSpacing: gap between tags / tagSize (unitless)
  int first_id = 0;           ///< firstId: id of the first tag (see AprilGridLayout)
  AprilGridLayout layout = AprilGridLayout::kKalibr;  ///< h4camLayout (absent: kKalibr)
  std::optional<double> size_sigma = std::nullopt;  ///< h4camSizeSigma (BoardSizeSigma)

  AprilGridDesign design() const { return DesignOf(layout); }
};

struct CheckerboardSpec {
  int cols = 9;                ///< targetCols: inner corners along a row
  int rows = 6;                ///< targetRows: inner corners along a column
  double col_spacing = 0.025;  ///< colSpacingMeters, m
  double row_spacing = 0.025;  ///< rowSpacingMeters, m
  std::optional<double> size_sigma = std::nullopt;  ///< h4camSizeSigma (BoardSizeSigma)
};

using BoardSpec = std::variant<AprilGridSpec, CheckerboardSpec>;

/// h4camSizeSigma: the relative one-sigma of the board's true size against its stated one
/// (a print measured with calipers to 0.02 %: 0.0002). A uniform scale of the board is not
/// observable with rotary joints (it scales every identified length), so the stated size
/// is the calibration's metric reference and this its uncertainty
/// (common/README.md#the-camera-files-uncertainty); nullopt when the file does not state it.
inline std::optional<double> BoardSizeSigma(const BoardSpec& board) {
  return std::visit([](const auto& spec) { return spec.size_sigma; }, board);
}

}  // namespace h4
