// The board YAML (common/formats/README.md#board-yaml---board, `--board`): an AprilTag grid with
// Kalibr's aprilgrid keys, or an OpenCV chessboard with Kalibr's checkerboard keys.
#pragma once

#include <string>
#include <vector>

#include "common/board/board_spec.h"

namespace h4 {

/// A tag family h4cam detects, renders and prints, with its number of codes (ids 0 to
/// codes - 1).
struct AprilTagFamilyInfo {
  std::string name;  ///< AprilTag's name, that of its tag*.h header
  int codes = 0;     ///< the family's ncodes in AprilTag 3.3
};

/// The families h4cam supports (firmware/detection/tag_family.cpp creates them; a test
/// checks the codes against libapriltag): tag36h11, tag25h9, tag16h5. AprilTag ships others
/// (tagCircle21h7, ...), which h4cam cannot detect, so a board of them is refused.
const std::vector<AprilTagFamilyInfo>& AprilTagFamilies();
/// The family called `name`, or nullptr when h4cam does not support it.
const AprilTagFamilyInfo* FindAprilTagFamily(const std::string& name);

/// Reads a board file. aprilgrid: tagCols, tagRows (positive integers), tagSize (m) and
/// tagSpacing (ratio), both positive; optional tagFamily (one of AprilTagFamilies(),
/// default tag36h11), firstId (>= 0, default 0; the grid's last id, firstId + tagCols x
/// tagRows - 1, must be a code of the family) and h4cam's own h4camLayout ('kalibr',
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
