// Board YAML; see board_yaml.h.
#include "common/formats/board_yaml.h"

#include <algorithm>
#include <optional>
#include <string>

#include <fmt/core.h>

#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"
#include "common/formats/yaml_map.h"

namespace h4 {
namespace {

std::string JoinedFamilyNames() {
  std::string text;
  for (const AprilTagFamilyInfo& family : AprilTagFamilies()) {
    text += (text.empty() ? "" : ", ") + family.name;
  }
  return text;
}

// Limits checked before anything is allocated from these numbers (tagRows: 2147483647
// ended in bad_alloc after 36 s): no printable board has more tags or corners per side,
// and no tag family more ids.
constexpr int64_t kMaxPerSide = 200;
constexpr int64_t kMaxFirstId = 100000;
constexpr double kMaxSize_m = 10.0;

int Count(const YamlMap& map, const std::string& key, int64_t minimum,
          int64_t maximum = kMaxPerSide) {
  const int64_t value = map.Int(key);
  if (value < minimum || value > maximum) {
    map.Fail(key, fmt::format("expected an integer in [{}, {}], got {}", minimum, maximum, value));
  }
  return static_cast<int>(value);
}

// h4cam's own key; a plain Kalibr file has none and means Kalibr's printed design.
const char* const kLayoutKey = "h4camLayout";

AprilGridLayout ReadLayout(const YamlMap& root) {
  const std::string name = root.String(kLayoutKey);
  if (name == "kalibr") return AprilGridLayout::kKalibr;
  if (name == "legacy") return AprilGridLayout::kH4Legacy;
  root.Fail(kLayoutKey, "unknown layout '" + name + "', expected 'kalibr' or 'legacy'");
}

// h4cam's own key: the stated size's relative one-sigma (board_spec.h BoardSizeSigma).
const char* const kSizeSigmaKey = "h4camSizeSigma";

std::optional<double> ReadSizeSigma(const YamlMap& root) {
  if (!root.Has(kSizeSigmaKey)) return std::nullopt;
  const double value = root.Double(kSizeSigmaKey);
  if (!(value >= 0.0 && value <= 0.1)) {
    root.Fail(kSizeSigmaKey, "expected a relative one-sigma in [0, 0.1] (0.0002: 0.02 %), got " +
                                 FormatDouble(value, kSizeSigmaKey));
  }
  return value;
}

std::string SizeSigmaLine(const std::optional<double>& sigma) {
  if (!sigma) return "";
  return std::string(kSizeSigmaKey) + ": " + FormatDouble(*sigma, kSizeSigmaKey) +
         "  # relative one-sigma of the printed size\n";
}

// A positive size no larger than kMaxSize_m (a ratio for tagSpacing).
double Size(const YamlMap& map, const std::string& key) {
  const double value = map.PositiveDouble(key);
  if (value > kMaxSize_m) {
    map.Fail(key, "expected at most " + FormatDouble(kMaxSize_m, key) + ", got " +
                      FormatDouble(value, key));
  }
  return value;
}

AprilGridSpec ReadAprilGrid(const YamlMap& root) {
  AprilGridSpec spec;
  if (root.Has("tagFamily")) {
    spec.tag_family = root.String("tagFamily");
    if (FindAprilTagFamily(spec.tag_family) == nullptr) {
      root.Fail("tagFamily", "unknown tag family '" + spec.tag_family + "', expected one of: " +
                                 JoinedFamilyNames() + " (the families h4cam detects)");
    }
  }
  spec.cols = Count(root, "tagCols", 1);
  spec.rows = Count(root, "tagRows", 1);
  spec.tag_size = Size(root, "tagSize");
  spec.tag_spacing = Size(root, "tagSpacing");
  if (root.Has("firstId")) spec.first_id = Count(root, "firstId", 0, kMaxFirstId);
  if (root.Has(kLayoutKey)) spec.layout = ReadLayout(root);
  spec.size_sigma = ReadSizeSigma(root);
  if (4 * spec.cols * spec.rows < kMinBoardCorners) {
    root.Fail("tagCols",
              fmt::format("a grid of {} x {} tags has {} corners; h4cam needs {} to measure a pose",
                          spec.cols, spec.rows, 4 * spec.cols * spec.rows, kMinBoardCorners));
  }
  // A tag id past the family's codes has no pattern: h4cam can neither print nor detect it
  // (plan accepted such a board, make-board and render refused it).
  const int codes = FindAprilTagFamily(spec.tag_family)->codes;
  const int64_t last_id = static_cast<int64_t>(spec.first_id) + spec.cols * spec.rows - 1;
  if (last_id >= codes) {
    root.Fail(root.Has("firstId") ? "firstId" : "tagCols",
              fmt::format("the grid's ids run from {} to {}, past the {} codes of {} (ids 0 to {})",
                          spec.first_id, last_id, codes, spec.tag_family, codes - 1));
  }
  return spec;
}

CheckerboardSpec ReadCheckerboard(const YamlMap& root) {
  CheckerboardSpec spec;
  // OpenCV's chessboard detectors assert on fewer per side: `h4cam measure` stopped with its
  // assertion text and `h4cam run` exited on its first capture request.
  spec.cols = Count(root, "targetCols", kMinChessboardCornersPerSide);
  spec.rows = Count(root, "targetRows", kMinChessboardCornersPerSide);
  if (spec.cols * spec.rows < kMinBoardCorners) {
    root.Fail("targetCols", fmt::format("{} x {} inner corners; h4cam needs {} to measure a pose",
                                        spec.cols, spec.rows, kMinBoardCorners));
  }
  spec.col_spacing = Size(root, "colSpacingMeters");
  spec.row_spacing = Size(root, "rowSpacingMeters");
  spec.size_sigma = ReadSizeSigma(root);
  return spec;
}

}  // namespace

const std::vector<AprilTagFamilyInfo>& AprilTagFamilies() {
  static const std::vector<AprilTagFamilyInfo> families = {
      {"tag36h11", 587}, {"tag25h9", 35}, {"tag16h5", 30}};
  return families;
}

const AprilTagFamilyInfo* FindAprilTagFamily(const std::string& name) {
  for (const AprilTagFamilyInfo& family : AprilTagFamilies()) {
    if (family.name == name) return &family;
  }
  return nullptr;
}

namespace {

// A camera file (OpenCV's or Kalibr's) where a board was expected: the two YAML files of
// h4cam's command lines are the easiest pair to swap.
void RejectCameraFile(const YamlMap& root, const std::string& source_name) {
  if (root.Has("target_type")) return;
  for (const char* camera_key : {"camera_matrix", "image_width", "camera_model", "cam0"}) {
    if (!root.Has(camera_key)) continue;
    throw FormatError(source_name, 1, "",
                      "this looks like a camera file, not a board YAML (were --board and --camera "
                      "swapped?)");
  }
}

}  // namespace

BoardSpec ParseBoardYaml(const std::string& text, const std::string& source_name) {
  const YamlMap root(LoadYaml(text, source_name), source_name, "", 0);
  RejectCameraFile(root, source_name);
  root.RejectCaseVariants({"target_type", "tagFamily", "tagCols", "tagRows", "tagSize",
                           "tagSpacing", "firstId", kLayoutKey, "targetCols", "targetRows",
                           "colSpacingMeters", "rowSpacingMeters", kSizeSigmaKey});
  const std::string type = root.String("target_type");
  if (type == "aprilgrid") return ReadAprilGrid(root);
  if (type == "checkerboard") return ReadCheckerboard(root);
  root.Fail("target_type",
            "unknown target type '" + type + "', expected 'aprilgrid' or 'checkerboard'");
}

BoardSpec ReadBoardYaml(const std::string& path) {
  return ParseBoardYaml(ReadTextFile(path), path);
}

std::string FormatBoardYaml(const BoardSpec& board) {
  std::string text = "# calibration board (common/formats/README.md \"Board\"; sizes in m)\n";
  if (const auto* grid = std::get_if<AprilGridSpec>(&board)) {
    text += fmt::format(
        "target_type: aprilgrid\n"
        "tagFamily: {}\n"
        "tagCols: {}\n"
        "tagRows: {}\n"
        "tagSize: {}  # m, outer edge of the black border\n"
        "tagSpacing: {}  # gap between tags = tagSpacing * tagSize\n"
        "firstId: {}\n",
        grid->tag_family, grid->cols, grid->rows, FormatDouble(grid->tag_size, "tagSize"),
        FormatDouble(grid->tag_spacing, "tagSpacing"), grid->first_id);
    if (grid->layout == AprilGridLayout::kH4Legacy) {
      text += std::string(kLayoutKey) +
              ": legacy  # 1-cell tag border, no corner squares, ids from the top-left\n";
    }
    text += SizeSigmaLine(grid->size_sigma);
  } else {
    const auto& chess = std::get<CheckerboardSpec>(board);
    text += fmt::format(
        "target_type: checkerboard\n"
        "targetCols: {}  # inner corners along a row\n"
        "targetRows: {}  # inner corners along a column\n"
        "colSpacingMeters: {}\n"
        "rowSpacingMeters: {}\n"
        "{}",
        chess.cols, chess.rows, FormatDouble(chess.col_spacing, "colSpacingMeters"),
        FormatDouble(chess.row_spacing, "rowSpacingMeters"), SizeSigmaLine(chess.size_sigma));
  }
  return text;
}

void WriteBoardYaml(const std::string& path, const BoardSpec& board) {
  WriteTextFile(path, FormatBoardYaml(board));
}

}  // namespace h4
