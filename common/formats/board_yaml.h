// The board YAML (common/formats/README.md "Board", `--board`): an AprilTag grid with Kalibr's
// aprilgrid keys, or an OpenCV chessboard with Kalibr's checkerboard keys.
#pragma once

#include <string>
#include <vector>

#include "common/board/board_spec.h"

namespace h4 {

/// The tag families AprilTag 3.3 ships (the names of its tag*.h headers).
const std::vector<std::string>& AprilTagFamilies();

/// Reads a board file. aprilgrid: tagCols, tagRows (positive integers), tagSize (m) and
/// tagSpacing (ratio), both positive; optional tagFamily (one of AprilTagFamilies(),
/// default tag36h11), firstId (>= 0, default 0) and h4cam's own h4camLayout ('kalibr',
/// the default: the design kalibr_create_target_pdf prints; 'legacy': h4cam's earlier
/// 1-cell-border design, board_spec.h AprilGridLayout). checkerboard: targetCols, targetRows
/// (inner corners, >= 2), colSpacingMeters, rowSpacingMeters (positive). An unknown
/// target_type is an error naming it and the accepted ones. Other keys (Kalibr's
/// codeOffset...) are ignored, except a known key spelt with other letter case
/// ("firstID"), which is an error rather than a silent default. Limits, checked before
/// anything is allocated: at most 200 tags or inner corners per side, firstId at most
/// 100000, sizes and tagSpacing at most 10.
BoardSpec ParseBoardYaml(const std::string& text, const std::string& source_name);
BoardSpec ReadBoardYaml(const std::string& path);

/// Writes the keys above (all of them, defaults included), shortest round-trip numbers.
std::string FormatBoardYaml(const BoardSpec& board);
void WriteBoardYaml(const std::string& path, const BoardSpec& board);

}  // namespace h4
