// The board-corner CSV (common/formats/README.md#board-corners-csv): the refined image
// corners a board pose was estimated from, one row per corner, so that the identification
// can fit in pixel space and refine the camera's intrinsics (host/identification).
//   pose_id,tag_id,corner,u,v[,sigma_px]
// `corner` is the board's corner id (common/board/board_model.h: 4 * (tag_id - firstId) + k
// for an AprilTag grid, row * targetCols + col for a chessboard, whose rows carry
// tag_id -1); (u, v) are pixels in OpenCV's convention ((0, 0) the centre of the top-left
// pixel); sigma_px the corner's standard deviation per axis, px (absent: the reader's
// default).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace h4 {

struct CornerObservation {
  int64_t pose_id = 0;
  int tag_id = -1;  ///< AprilTag id, -1 for a chessboard corner
  int corner = 0;   ///< corner id on the board (BoardModel)
  double u = 0;     ///< px, OpenCV convention
  double v = 0;
  std::optional<double> sigma_px;  ///< per-axis std, px
};

/// The corner standard deviations a file may carry: 1e-6 px up to 100 px.
struct CornerSigmaBounds {
  double min;
  double max;
};
inline constexpr CornerSigmaBounds kCornerSigmaBounds{1e-6, 100.0};

/// Reads a corner CSV; throws FormatError naming file, line and field on malformed input
/// (missing column, non-number or non-finite value, a pixel coordinate beyond +-1e6 px, a
/// sigma outside kCornerSigmaBounds, the same (pose_id, corner) twice). A file with no corner
/// row (only its header) is refused too: every command that reads one needs corners.
/// Whether tag_id belongs to the board is checked where the corners meet the board
/// (CornerOnBoard, common/board/board_model.h).
std::vector<CornerObservation> ReadCornersCsv(const std::string& path);
std::vector<CornerObservation> ParseCornersCsv(const std::string& text,
                                               const std::string& source_name);

/// Header line (no newline) and one row, shortest round-trip numbers, for writers that
/// append durably (the campaign); the sigma_px column when `with_sigma`.
std::string CornersCsvHeader(bool with_sigma);
std::string CornersCsvLine(const CornerObservation& c, bool with_sigma);
/// Whole file (sigma column when any row has one), replaced atomically.
void WriteCornersCsv(const std::string& path, const std::vector<CornerObservation>& corners);

}  // namespace h4
