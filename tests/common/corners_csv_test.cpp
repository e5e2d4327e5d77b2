// Board-corner CSV (common/formats/README.md#board-corners-csv): exact round trip, an
// AprilTag and a chessboard row, CRLF and BOM, and each refusal with its line and field.
#include "common/formats/corners_csv.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "common/formats/csv_table.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

const std::string kHeader = "pose_id,tag_id,corner,u,v,sigma_px\n";

TEST(CornersCsv, ReadsTagAndChessboardRows) {
  const std::vector<CornerObservation> corners = ParseCornersCsv(kHeader +
                                                                     "7,3,13,640.25,-0.5,0.02\n"
                                                                     "8,-1,41,12.5,900,\n",
                                                                 "c.csv");
  ASSERT_EQ(corners.size(), 2u);
  EXPECT_EQ(corners[0].pose_id, 7);
  EXPECT_EQ(corners[0].tag_id, 3);
  EXPECT_EQ(corners[0].corner, 13);
  EXPECT_EQ(corners[0].u, 640.25);
  EXPECT_EQ(corners[0].v, -0.5);
  EXPECT_EQ(corners[0].sigma_px, 0.02);
  EXPECT_EQ(corners[1].pose_id, 8);
  EXPECT_EQ(corners[1].tag_id, -1);
  EXPECT_EQ(corners[1].corner, 41);
  EXPECT_FALSE(corners[1].sigma_px.has_value());
}

TEST(CornersCsv, SigmaColumnIsOptionalAndColumnsMayMoveCrlfAndBomRead) {
  const std::vector<CornerObservation> corners =
      ParseCornersCsv("\xEF\xBB\xBFv,u,corner,tag_id,pose_id,extra\r\n2,1,0,0,5,x\r\n", "c.csv");
  ASSERT_EQ(corners.size(), 1u);
  EXPECT_EQ(corners[0].pose_id, 5);
  EXPECT_EQ(corners[0].u, 1.0);
  EXPECT_EQ(corners[0].v, 2.0);
  EXPECT_FALSE(corners[0].sigma_px.has_value());
}

TEST(CornersCsv, RoundTripIsExact) {
  std::vector<CornerObservation> corners(3);
  corners[0] = {1, 0, 0, 1.0 / 3, 479.123456789012, 0.0123};
  corners[1] = {1, 0, 3, 1e-7, 2.0 / 7, std::nullopt};
  corners[2] = {2, -1, 17, 1279.5, 0.1 + 0.2, 1e-6};
  const std::string path = TempPath("corners.csv");
  WriteCornersCsv(path, corners);
  const std::vector<CornerObservation> back = ReadCornersCsv(path);
  ASSERT_EQ(back.size(), corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    EXPECT_EQ(back[i].pose_id, corners[i].pose_id);
    EXPECT_EQ(back[i].tag_id, corners[i].tag_id);
    EXPECT_EQ(back[i].corner, corners[i].corner);
    EXPECT_EQ(back[i].u, corners[i].u);
    EXPECT_EQ(back[i].v, corners[i].v);
    EXPECT_EQ(back[i].sigma_px, corners[i].sigma_px);
  }
}

TEST(CornersCsv, HeaderAndLineHaveTheDocumentedFirstColumns) {
  EXPECT_EQ(CornersCsvHeader(false), "pose_id,tag_id,corner,u,v");
  EXPECT_EQ(CornersCsvHeader(true), "pose_id,tag_id,corner,u,v,sigma_px");
  EXPECT_EQ(CornersCsvLine({12, -1, 4, 0.5, 2, 0.25}, true), "12,-1,4,0.5,2,0.25");
  EXPECT_EQ(CornersCsvLine({12, 2, 9, 0.5, 2, std::nullopt}, true), "12,2,9,0.5,2,");
  EXPECT_EQ(CornersCsvLine({12, 2, 9, 0.5, 2, 0.25}, false), "12,2,9,0.5,2");
}

TEST(CornersCsv, WithoutAnySigmaTheFileHasNoSigmaColumn) {
  const std::string path = TempPath("corners.csv");
  WriteCornersCsv(path, {{3, 1, 5, 10, 20, std::nullopt}});
  EXPECT_EQ(ReadTextFile(path), "pose_id,tag_id,corner,u,v\n3,1,5,10,20\n");
}

TEST(CornersCsv, WriterRefusesANonFiniteCoordinate) {
  EXPECT_THROW(CornersCsvLine({1, 0, 0, std::nan(""), 0, std::nullopt}, false),
               std::invalid_argument);
}

TEST(CornersCsvErrors, NameLineAndField) {
  ExpectEachFailsWith(
      ParseCornersCsv, "c.csv",
      {{"pose_id,tag_id,corner,u\n", 1, "v", "missing column"},
       {"pose_id,corner,u,v\n", 1, "tag_id", "missing column"},
       {kHeader + "x,0,0,1,1,\n", 2, "pose_id", "expected an integer"},
       {kHeader + "1,-2,0,1,1,\n", 2, "tag_id", "-1 for a chessboard"},
       {kHeader + "1,0,-1,1,1,\n", 2, "corner", "non-negative"},
       {kHeader + "1,0,2.5,1,1,\n", 2, "corner", "expected an integer"},
       {kHeader + "1,0,0,,1,\n", 2, "u", "expected a number"},
       {kHeader + "1,0,0,1,nan,\n", 2, "v", "expected a number"},
       {kHeader + "1,0,0,1,inf,\n", 2, "v", "expected a number"},
       {kHeader + "1,0,0,1e7,1,\n", 2, "u", "+-1e6"},
       {kHeader + "1,0,0,1,-2e6,\n", 2, "v", "+-1e6"},
       {kHeader + "1,0,0,1,1,0\n", 2, "sigma_px", "standard deviation"},
       {kHeader + "1,0,0,1,1,1e-7\n", 2, "sigma_px", "standard deviation"},
       {kHeader + "1,0,0,1,1,101\n", 2, "sigma_px", "standard deviation"},
       {kHeader + "1,0,0,1,1,-0.1\n", 2, "sigma_px", "standard deviation"},
       {kHeader + "1,0,0,1,1,\n2,0,0,1,1,\n1,0,0,3,3,\n", 4, "corner", "appears twice"},
       {kHeader + "1,0,0,1,1\n", 2, "sigma_px", "missing field"},
       {kHeader + "1,0,0,1,1,\r2,0,0,1,1,\n", 2, "", "carriage return"}});
}

// Issue 42 point 16: a file without its header said "field '0': column appears twice in the
// header" (the first data row read as column names); it says the header is missing.
TEST(CornersCsvErrors, AMissingHeaderIsNamedAsSuch) {
  EXPECT_TRUE(FailsWith([] { ParseCornersCsv("1,0,0,100.5,200.25\n1,0,1,110,200\n", "c.csv"); },
                        "c.csv", 1, "", "the header is missing"));
  EXPECT_TRUE(FailsWith([] { ParseCornersCsv("1,-1,0,1e2,2,0.1\n", "c.csv"); }, "c.csv", 1, "",
                        "the header is missing"));
}

// Issue 42 point 16: a corners file with its header and no row gave "no corners given" and
// exit 0 (validate); the reader of a command's corners file refuses it naming the file.
TEST(CornersCsvErrors, AHeaderOnlyFileIsAnErrorNamingIt) {
  const std::string path = TempPath("header_only.csv");
  WriteTextFile(path, kHeader);
  EXPECT_TRUE(FailsWith([&] { ReadCornersCsv(path); }, path, 0, "", "no corner rows"));
  EXPECT_TRUE(ParseCornersCsv(kHeader, path).empty()) << "the campaign's journal starts so";
}

TEST(CornersCsvErrors, AnUnreadableFileIsAFormatErrorNamingIt) {
  const std::string path = TempPath("missing.csv");
  EXPECT_TRUE(FailsWith([&] { ReadCornersCsv(path); }, path, 0, ""));
}

}  // namespace
}  // namespace h4
