// Board YAML: the aprilgrid example of common/formats/README.md, a plain Kalibr file
// (Kalibr's design) and the legacy layout key, Kalibr-style checkerboard, defaults, round
// trip, and every kind of malformed value with its line and field.
#include "common/formats/board_yaml.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/support/board_specs.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

const std::string kAprilGrid = R"(target_type: aprilgrid
tagFamily: tag36h11        # optional, default tag36h11
tagCols: 6
tagRows: 6
tagSize: 0.024             # m, outer edge of the black border
tagSpacing: 0.25           # gap between tags = tagSpacing * tagSize
firstId: 0                 # optional, default 0
)";

const std::string kCheckerboard = R"(target_type: checkerboard
targetCols: 9
targetRows: 6
colSpacingMeters: 0.025
rowSpacingMeters: 0.03
)";

TEST(BoardYaml, ReadsTheAprilGridExampleOfFormatsMd) {
  const BoardSpec board = ParseBoardYaml(kAprilGrid, "board.yaml");
  const auto* grid = std::get_if<AprilGridSpec>(&board);
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid->tag_family, "tag36h11");
  EXPECT_EQ(grid->cols, 6);
  EXPECT_EQ(grid->rows, 6);
  EXPECT_EQ(grid->tag_size, 0.024);
  EXPECT_EQ(grid->tag_spacing, 0.25);
  EXPECT_EQ(grid->first_id, 0);
}

TEST(BoardYaml, OptionalKeysTakeTheirDefaults) {
  const BoardSpec board = ParseBoardYaml(
      "target_type: aprilgrid\ntagCols: 4\ntagRows: 3\ntagSize: 0.05\ntagSpacing: 0.3\n"
      "codeOffset: 0  # Kalibr's, ignored\n",
      "b.yaml");
  const AprilGridSpec grid = std::get<AprilGridSpec>(board);
  EXPECT_EQ(grid.tag_family, "tag36h11");
  EXPECT_EQ(grid.first_id, 0);
  EXPECT_EQ(grid.cols, 4);
  EXPECT_EQ(grid.rows, 3);
  const AprilGridSpec other = std::get<AprilGridSpec>(
      ParseBoardYaml("target_type: aprilgrid\ntagFamily: tag25h9\ntagCols: 4\ntagRows: 3\n"
                     "tagSize: 0.05\ntagSpacing: 0.3\nfirstId: 20\n",
                     "b.yaml"));
  EXPECT_EQ(other.tag_family, "tag25h9");
  EXPECT_EQ(other.first_id, 20);
}

// A target file as Kalibr's documentation writes it: no h4cam key, so Kalibr's design.
TEST(BoardYaml, PlainKalibrFileMeansKalibrsPrintedDesign) {
  const AprilGridSpec grid = std::get<AprilGridSpec>(ParseBoardYaml(
      "target_type: 'aprilgrid'\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.3\n",
      "april_6x6.yaml"));
  EXPECT_EQ(grid.layout, AprilGridLayout::kKalibr);
  EXPECT_EQ(grid.design().border_cells, 2);
  EXPECT_TRUE(grid.design().corner_squares);
  EXPECT_TRUE(grid.design().ids_from_bottom);
  EXPECT_EQ(grid.tag_size, 0.088);
}

TEST(BoardYaml, LayoutKeySelectsTheDesign) {
  const auto layout_of = [](const std::string& value) {
    return std::get<AprilGridSpec>(
               ParseBoardYaml(kAprilGrid + "h4camLayout: " + value + "\n", "b.yaml"))
        .layout;
  };
  EXPECT_EQ(layout_of("legacy"), AprilGridLayout::kH4Legacy);
  EXPECT_EQ(layout_of("kalibr"), AprilGridLayout::kKalibr);
  const AprilGridDesign legacy = DesignOf(AprilGridLayout::kH4Legacy);
  EXPECT_EQ(legacy.border_cells, 1);
  EXPECT_FALSE(legacy.corner_squares);
  EXPECT_FALSE(legacy.ids_from_bottom);
}

TEST(BoardYaml, KalibrBoardIsWrittenWithoutTheLayoutKeyAndLegacyWithIt) {
  AprilGridSpec grid;
  EXPECT_EQ(FormatBoardYaml(grid).find("h4camLayout"), std::string::npos);
  grid.layout = AprilGridLayout::kH4Legacy;
  const std::string text = FormatBoardYaml(grid);
  EXPECT_NE(text.find("h4camLayout: legacy"), std::string::npos);
  EXPECT_EQ(std::get<AprilGridSpec>(ParseBoardYaml(text, "mem")).layout,
            AprilGridLayout::kH4Legacy);
}

TEST(BoardYaml, ReadsACheckerboard) {
  const BoardSpec board = ParseBoardYaml(kCheckerboard, "c.yaml");
  const auto* chess = std::get_if<CheckerboardSpec>(&board);
  ASSERT_NE(chess, nullptr);
  EXPECT_EQ(chess->cols, 9);
  EXPECT_EQ(chess->rows, 6);
  EXPECT_EQ(chess->col_spacing, 0.025);
  EXPECT_EQ(chess->row_spacing, 0.03);
}

TEST(BoardYaml, FamiliesAreThoseAprilTagShips) {
  for (const AprilTagFamilyInfo& family : AprilTagFamilies()) {
    EXPECT_TRUE(std::filesystem::exists("/usr/include/apriltag/" + family.name + ".h") ||
                !std::filesystem::exists("/usr/include/apriltag"))
        << family.name;
  }
}

TEST(BoardYaml, RoundTripIsExact) {
  AprilGridSpec grid;
  grid.tag_family = "tag25h9";  // 35 codes: ids 12 to 31
  grid.cols = 4;
  grid.rows = 5;
  grid.tag_size = 0.1 / 3;
  grid.tag_spacing = 0.3;
  grid.first_id = 12;
  const auto back = std::get<AprilGridSpec>(ParseBoardYaml(FormatBoardYaml(grid), "mem"));
  EXPECT_EQ(back.tag_family, grid.tag_family);
  EXPECT_EQ(back.cols, grid.cols);
  EXPECT_EQ(back.rows, grid.rows);
  EXPECT_EQ(back.tag_size, grid.tag_size);
  EXPECT_EQ(back.tag_spacing, grid.tag_spacing);
  EXPECT_EQ(back.first_id, grid.first_id);
  EXPECT_EQ(back.layout, grid.layout);
  grid.size_sigma = 2e-4;
  EXPECT_EQ(std::get<AprilGridSpec>(ParseBoardYaml(FormatBoardYaml(grid), "mem")).size_sigma, 2e-4);
  const CheckerboardSpec chess = Chessboard(11, 8, 0.0251, 0.0249);
  const std::string path = TempPath("board.yaml");
  WriteBoardYaml(path, chess);
  const auto chess_back = std::get<CheckerboardSpec>(ReadBoardYaml(path));
  EXPECT_EQ(chess_back.cols, 11);
  EXPECT_EQ(chess_back.rows, 8);
  EXPECT_EQ(chess_back.col_spacing, 0.0251);
  EXPECT_EQ(chess_back.row_spacing, 0.0249);
  EXPECT_FALSE(chess_back.size_sigma.has_value());
}

// h4camSizeSigma: the stated size's relative one-sigma, in [0, 0.1].
TEST(BoardYamlErrors, SizeSigmaIsARelativeSigma) {
  const std::string grid =
      "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.03\ntagSpacing: 0.25\n";
  EXPECT_EQ(BoardSizeSigma(ParseBoardYaml(grid + "h4camSizeSigma: 0.0005\n", "b.yaml")), 5e-4);
  EXPECT_FALSE(BoardSizeSigma(ParseBoardYaml(grid, "b.yaml")).has_value());
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(grid + "h4camSizeSigma: 0.5\n", "b.yaml"); }, "b.yaml",
                        6, "h4camSizeSigma", "relative one-sigma in [0, 0.1]"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(grid + "h4camSizeSigma: -1e-4\n", "b.yaml"); },
                        "b.yaml", 6, "h4camSizeSigma", "relative one-sigma"));
}

TEST(BoardYamlErrors, UnknownTargetTypeNamesTheAcceptedOnes) {
  EXPECT_TRUE(FailsWith([] { ParseBoardYaml("# board\ntarget_type: charuco\n", "b.yaml"); },
                        "b.yaml", 2, "target_type",
                        "unknown target type 'charuco', expected 'aprilgrid' or 'checkerboard'"));
  EXPECT_TRUE(FailsWith([] { ParseBoardYaml("tagCols: 6\n", "b.yaml"); }, "b.yaml", 0,
                        "target_type", "missing key"));
}

TEST(BoardYamlErrors, KnownKeyInOtherCaseIsNotIgnored) {
  const std::string text = ReplacedOnce(kAprilGrid, "firstId: 0", "firstID: 5");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(text, "b.yaml"); }, "b.yaml", 7, "firstID",
                        "case-sensitive: 'firstId'"));
}

TEST(BoardYamlErrors, UnknownLayoutNamesTheAcceptedOnes) {
  EXPECT_TRUE(FailsWith([] { ParseBoardYaml(kAprilGrid + "h4camLayout: kalibr2\n", "b.yaml"); },
                        "b.yaml", 8, "h4camLayout",
                        "unknown layout 'kalibr2', expected 'kalibr' or 'legacy'"));
  EXPECT_TRUE(FailsWith([] { ParseBoardYaml(kAprilGrid + "h4camlayout: legacy\n", "b.yaml"); },
                        "b.yaml", 8, "h4camlayout", "case-sensitive: 'h4camLayout'"));
}

TEST(BoardYamlErrors, UnknownTagFamily) {
  const std::string text = ReplacedOnce(kAprilGrid, "tag36h11", "tag36h12");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(text, "b.yaml"); }, "b.yaml", 2, "tagFamily",
                        "unknown tag family 'tag36h12', expected one of: tag36h11"));
}

// Issue 27 point 4: plan accepted boards h4cam cannot measure: a family AprilTag ships but
// h4cam does not detect, and ids past the family's codes (make-board and render refused them).
TEST(BoardYamlErrors, FamiliesAndIdsH4camCannotDetectAreRefused) {
  const std::string circle = ReplacedOnce(kAprilGrid, "tag36h11", "tagCircle21h7");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(circle, "b.yaml"); }, "b.yaml", 2, "tagFamily",
                        "unknown tag family 'tagCircle21h7', expected one of: tag36h11, "
                        "tag25h9, tag16h5 (the families h4cam detects)"));
  // tag36h11 has 587 codes: 36 tags from 552 end at 587.
  const std::string past = ReplacedOnce(kAprilGrid, "firstId: 0", "firstId: 552");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(past, "b.yaml"); }, "b.yaml", 7, "firstId",
                        "the grid's ids run from 552 to 587, past the 587 codes of tag36h11 "
                        "(ids 0 to 586)"));
  const auto last = std::get<AprilGridSpec>(
      ParseBoardYaml(ReplacedOnce(kAprilGrid, "firstId: 0", "firstId: 551"), "b.yaml"));
  EXPECT_EQ(last.first_id, 551);
  // tag16h5 has 30 codes: a 6 x 6 grid needs 36, even from id 0.
  const std::string small = ReplacedOnce(kAprilGrid, "tag36h11", "tag16h5");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(small, "b.yaml"); }, "b.yaml", 7, "firstId",
                        "past the 30 codes of tag16h5"));
}

TEST(BoardYamlErrors, NonPositiveCountsAndSizes) {
  const auto with = [](const std::string& from, const std::string& to) {
    return ReplacedOnce(kAprilGrid, from, to);
  };
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(with("tagCols: 6", "tagCols: 0"), "b.yaml"); },
                        "b.yaml", 3, "tagCols", "expected an integer in [1, 200], got 0"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(with("tagRows: 6", "tagRows: 6.5"), "b.yaml"); },
                        "b.yaml", 4, "tagRows", "expected an integer"));
  EXPECT_TRUE(
      FailsWith([&] { ParseBoardYaml(with("tagSize: 0.024", "tagSize: -0.024"), "b.yaml"); },
                "b.yaml", 5, "tagSize", "positive"));
  EXPECT_TRUE(
      FailsWith([&] { ParseBoardYaml(with("tagSpacing: 0.25", "tagSpacing: 0"), "b.yaml"); },
                "b.yaml", 6, "tagSpacing", "positive"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(with("firstId: 0", "firstId: -1"), "b.yaml"); },
                        "b.yaml", 7, "firstId", "in [0, 100000], got -1"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(with("tagSize: 0.024", "tagSize: 24mm"), "b.yaml"); },
                        "b.yaml", 5, "tagSize", "expected a number, got '24mm'"));
  std::string chess = ReplacedOnce(kCheckerboard, "targetRows: 6", "targetRows: 1");
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(chess, "c.yaml"); }, "c.yaml", 3, "targetRows",
                        "in [3, 200], got 1"));
  chess = kCheckerboard;
  chess.erase(chess.find("rowSpacingMeters"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(chess, "c.yaml"); }, "c.yaml", 0, "rowSpacingMeters",
                        "missing key"));
}

// issue 27 point 9: a checkerboard of 2 inner corners per side was read; OpenCV's detector
// asserts on it and `h4cam run` exited on the first capture request. A board h4cam cannot
// measure (under 3 per side, fewer than 12 corners in all) is refused naming the field.
TEST(BoardYamlErrors, BoardsTooSmallToMeasureAreRefused) {
  const auto chess = [](int cols, int rows) {
    return ReplacedOnce(
        ReplacedOnce(kCheckerboard, "targetCols: 9", fmt::format("targetCols: {}", cols)),
        "targetRows: 6", fmt::format("targetRows: {}", rows));
  };
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(chess(2, 2), "c.yaml"); }, "c.yaml", 2, "targetCols",
                        "in [3, 200], got 2"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(chess(9, 2), "c.yaml"); }, "c.yaml", 3, "targetRows",
                        "in [3, 200], got 2"));
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(chess(3, 3), "c.yaml"); }, "c.yaml", 2, "targetCols",
                        "3 x 3 inner corners; h4cam needs 12"));
  EXPECT_NO_THROW(ParseBoardYaml(chess(3, 4), "c.yaml"));
  const auto grid = [](int cols, int rows) {
    return ReplacedOnce(ReplacedOnce(kAprilGrid, "tagCols: 6", fmt::format("tagCols: {}", cols)),
                        "tagRows: 6", fmt::format("tagRows: {}", rows));
  };
  EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(grid(1, 1), "b.yaml"); }, "b.yaml", 3, "tagCols",
                        "1 x 1 tags has 4 corners; h4cam needs 12"));
  EXPECT_TRUE(
      FailsWith([&] { ParseBoardYaml(grid(2, 1), "b.yaml"); }, "b.yaml", 3, "tagCols", "needs 12"));
  EXPECT_NO_THROW(ParseBoardYaml(grid(3, 1), "b.yaml"));
}

// Regression: tagRows: 2147483647 ended in bad_alloc after 36 s. Counts and sizes are
// bounded when read, before anything is allocated from them.
TEST(BoardYamlErrors, CountsAndSizesAboveTheLimitsNameTheField) {
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseBoardYaml(ReplacedOnce(kAprilGrid, "tagRows: 6", "tagRows: 2147483647"), "b.yaml");
      },
      "b.yaml", 4, "tagRows", "expected an integer in [1, 200], got 2147483647"));
  EXPECT_TRUE(FailsWith(
      [&] { ParseBoardYaml(ReplacedOnce(kAprilGrid, "tagCols: 6", "tagCols: 201"), "b.yaml"); },
      "b.yaml", 3, "tagCols", "[1, 200]"));
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseBoardYaml(ReplacedOnce(kAprilGrid, "firstId: 0", "firstId: 4000000000"), "b.yaml");
      },
      "b.yaml", 7, "firstId", "[0, 100000]"));
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseBoardYaml(ReplacedOnce(kAprilGrid, "tagSize: 0.024", "tagSize: 1e300"), "b.yaml");
      },
      "b.yaml", 5, "tagSize", "at most 10"));
  EXPECT_TRUE(FailsWith(
      [&] {
        ParseBoardYaml(ReplacedOnce(kCheckerboard, "targetRows: 6", "targetRows: 100000"),
                       "b.yaml");
      },
      "b.yaml", 3, "targetRows", "[3, 200]"));
  // 200 rows of 2 tags: 400 ids, within tag36h11's 587.
  EXPECT_NO_THROW(
      ParseBoardYaml(ReplacedOnce(ReplacedOnce(kAprilGrid, "tagRows: 6", "tagRows: 200"),
                                  "tagCols: 6", "tagCols: 2"),
                     "b.yaml"));
}

// --board and --camera swapped: one line that names the mix-up (issue 26 point 8), for
// OpenCV's camera file and Kalibr's camchain.
TEST(BoardYaml, ACameraFileGivenAsTheBoardSaysTheyWereSwapped) {
  const std::string opencv_camera =
      "%YAML:1.0\n---\nimage_width: 1024\nimage_height: 768\ncamera_matrix: !!opencv-matrix\n"
      "  rows: 3\n  cols: 3\n  dt: d\n  data: [800, 0, 512, 0, 800, 384, 0, 0, 1]\n";
  const std::string kalibr_camchain =
      "cam0:\n  camera_model: pinhole\n  intrinsics: [800, 800, 512, 384]\n";
  for (const std::string& text : {opencv_camera, kalibr_camchain}) {
    EXPECT_TRUE(FailsWith([&] { ParseBoardYaml(text, "camera.yaml"); }, "camera.yaml", 1, "",
                          "this looks like a camera file, not a board YAML (were --board and "
                          "--camera swapped?)"));
  }
}

}  // namespace
}  // namespace h4
