// The shared CSV table: header, any column order, comments, CRLF, quoting, strict cells.
#include "common/formats/csv_table.h"

#include <gtest/gtest.h>

#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

TEST(CsvTable, FindsColumnsByNameSkippingCommentsAndBlankLines) {
  const CsvTable t = CsvTable::Parse(
      "# a comment\r\n\r\nb, a ,c\r\n  # another\r\n2, 1.5,\"x, y\"\r\n\n4,-3,\"say "
      "\"\"hi\"\"\"\r\n",
      "t.csv");
  EXPECT_EQ(t.header_line(), 3);
  ASSERT_EQ(t.num_rows(), 2u);
  EXPECT_EQ(t.line(0), 5);
  EXPECT_EQ(t.line(1), 7);
  EXPECT_EQ(t.GetDouble(0, "a"), 1.5);
  EXPECT_EQ(t.GetInt64(0, "b"), 2);
  EXPECT_EQ(t.GetString(0, "c"), "x, y");
  EXPECT_EQ(t.GetString(1, "c"), "say \"hi\"");
  EXPECT_EQ(t.GetDouble(1, "a"), -3.0);
  EXPECT_FALSE(t.HasColumn("d"));
  EXPECT_FALSE(t.GetOptionalDouble(0, "d").has_value());
}

TEST(CsvTable, StripsAByteOrderMark) {
  const CsvTable t = CsvTable::Parse("\xEF\xBB\xBFpose_id\n3\n", "t.csv");
  EXPECT_EQ(t.GetInt64(0, "pose_id"), 3);
}

TEST(CsvTable, EmptyCellIsAnOptionalButNotANumber) {
  const CsvTable t = CsvTable::Parse("a,b\n1,\n", "t.csv");
  EXPECT_FALSE(t.GetOptionalDouble(0, "b").has_value());
  EXPECT_TRUE(FailsWith([&] { t.GetDouble(0, "b"); }, "t.csv", 2, "b", "expected a number"));
  EXPECT_TRUE(FailsWith([&] { t.GetString(0, "b"); }, "t.csv", 2, "b", "expected a value"));
}

TEST(CsvTable, NamesLineAndColumnOfABadCell) {
  const CsvTable t = CsvTable::Parse("a,b\n1,2\n3,1.0abc\n4,nan\n1.5,inf\n", "t.csv");
  EXPECT_TRUE(
      FailsWith([&] { t.GetDouble(1, "b"); }, "t.csv", 3, "b", "expected a number, got '1.0abc'"));
  EXPECT_TRUE(FailsWith([&] { t.GetDouble(2, "b"); }, "t.csv", 4, "b", "got 'nan'"));
  EXPECT_TRUE(FailsWith([&] { t.GetDouble(3, "b"); }, "t.csv", 5, "b", "got 'inf'"));
  EXPECT_TRUE(
      FailsWith([&] { t.GetInt64(3, "a"); }, "t.csv", 5, "a", "expected an integer, got '1.5'"));
}

TEST(CsvTable, RequiresColumnsOnTheHeaderLine) {
  const CsvTable t = CsvTable::Parse("\n# c\na,b\n1,2\n", "t.csv");
  EXPECT_NO_THROW(t.RequireColumns({"b", "a"}));
  EXPECT_TRUE(FailsWith([&] { t.RequireColumns({"a", "z"}); }, "t.csv", 3, "z", "missing column"));
}

TEST(CsvTable, RejectsMalformedStructure) {
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("", "e.csv"); }, "e.csv", 0, "", "no header"));
  EXPECT_TRUE(
      FailsWith([] { CsvTable::Parse("# only\n\n", "e.csv"); }, "e.csv", 0, "", "no header"));
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,b,a\n", "d.csv"); }, "d.csv", 1, "a", "twice"));
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,,b\n", "d.csv"); }, "d.csv", 1, "", "no name"));
  // A short row names the first missing column.
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,b,c\n1,2,3\n1,2\n", "s.csv"); }, "s.csv", 3, "c",
                        "missing field"));
  EXPECT_TRUE(
      FailsWith([] { CsvTable::Parse("a,b\n1,2,3\n", "l.csv"); }, "l.csv", 2, "", "3 fields"));
  EXPECT_TRUE(
      FailsWith([] { CsvTable::Parse("a,b\n\"1,2\n", "q.csv"); }, "q.csv", 2, "", "unterminated"));
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,b\n\"1\"x,2\n", "q.csv"); }, "q.csv", 2, "",
                        "after a quoted field"));
}

// Regression: a file with CR-only line ends read as one header line and no row, and
// identify crashed on it. LF and CRLF are line ends; a CR alone is named.
TEST(CsvTable, CarriageReturnAloneIsAnErrorNamingTheLine) {
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,b\r1,2\r3,4\r", "cr.csv"); }, "cr.csv", 1, "",
                        "carriage return inside a line"));
  EXPECT_TRUE(FailsWith([] { CsvTable::Parse("a,b\n1,2\r3,4\n", "cr.csv"); }, "cr.csv", 2, "",
                        "LF or CRLF"));
  const CsvTable crlf = CsvTable::Parse("a,b\r\n1,2\r\n3,4\r\n", "crlf.csv");
  EXPECT_EQ(crlf.num_rows(), 2u);
}

TEST(CsvQuote, QuotesOnlyWhatTheReaderWouldAlter) {
  EXPECT_EQ(CsvQuote("img_001.png"), "img_001.png");
  EXPECT_EQ(CsvQuote("a,b"), "\"a,b\"");
  EXPECT_EQ(CsvQuote("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvQuote("#1"), "\"#1\"");
  EXPECT_EQ(CsvQuote(" x"), "\" x\"");
  EXPECT_THROW(CsvQuote("a\nb"), std::invalid_argument);
  const std::string cell = " odd, \"name\" ";
  const CsvTable t = CsvTable::Parse("c\n" + CsvQuote(cell) + "\n", "t.csv");
  EXPECT_EQ(t.GetString(0, "c"), cell);
}

TEST(ReadTextFile, NamesAMissingFile) {
  const std::string path = TempPath("does_not_exist.csv");
  EXPECT_TRUE(FailsWith([&] { ReadTextFile(path); }, path, 0, "", "cannot open"));
}

}  // namespace
}  // namespace h4
