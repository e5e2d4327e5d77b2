// The paired dataset CSV: known values, exact round trip, and one test per kind of
// malformed input, each checking the reported line and field.
#include "host/formats/dataset_csv.h"

#include <numbers>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "common/geometry/rotation.h"
#include "tests/host_formats/dataset_rows_helpers.h"
#include "tests/support/format_error_helpers.h"

namespace h4 {
namespace {

const std::string kDatasetHeader = "pose_id,utime,q1,q2,q3,q4,x,y,z,qw,qx,qy,qz";

// Line 1 header, line 2 a good row, line 3 the row under test.
std::string WithRow(const std::string& row, const std::string& header = kDatasetHeader) {
  return header + "\n0,100,0,0,0,0,0,0,1,1,0,0,0\n" + row + "\n";
}

TEST(DatasetCsv, ReadsKnownValuesWithColumnsInAnyOrder) {
  const std::string text =
      "# recorded 2026-11-21\r\n"
      "note,qz,qy,qx,qw,z,y,x,q4,q3,q2,q1,utime,pose_id\r\n"
      "\r\n"
      "first,0,0,1,0,1.05,-0.02,0.01,-3.1,3.0,0.5,-0.25,1700000000000000,7\r\n";
  const std::vector<DatasetRow> rows = ParseDatasetCsv(text, "d.csv");
  ASSERT_EQ(rows.size(), 1u);
  const DatasetRow& r = rows[0];
  EXPECT_EQ(r.pose_id, 7);
  EXPECT_EQ(r.utime, 1700000000000000);
  EXPECT_EQ(r.q[0], -0.25);
  EXPECT_EQ(r.q[1], 0.5);
  EXPECT_EQ(r.q[2], 3.0);
  EXPECT_EQ(r.q[3], -3.1);
  EXPECT_EQ(r.X_CT.translation(), Eigen::Vector3d(0.01, -0.02, 1.05));
  // q = (0, 1, 0, 0): half a turn about x.
  EXPECT_TRUE(
      r.X_CT.rotation().isApprox(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix(), 1e-15));
  EXPECT_FALSE(r.set.has_value());
  EXPECT_FALSE(r.sigma_t.has_value());
  EXPECT_FALSE(r.sigma_r.has_value());
}

TEST(DatasetCsv, AcceptsEitherQuaternionSignAndNormWithinTolerance) {
  const std::vector<DatasetRow> rows =
      ParseDatasetCsv(WithRow("1,0,0,0,0,0,0,0,0,-1,0,0,0\n2,0,0,0,0,0,0,0,0,0,0,0,1.0009"), "d");
  EXPECT_TRUE(rows[1].X_CT.rotation().isApprox(Eigen::Matrix3d::Identity(), 1e-15));
  EXPECT_TRUE(rows[2].X_CT.rotation().isApprox(RotZ(std::numbers::pi), 1e-15));
}

TEST(DatasetCsv, ReadsSetAndSigmaColumns) {
  const std::string text = kDatasetHeader +
                           ",set,sigma_t,sigma_r\n"
                           "1,5,0,0,0,0,0,0,1,1,0,0,0,calib,0.0001,0.002\n"
                           "2,6,0,0,0,0,0,0,1,1,0,0,0,valid,,\n";
  const std::vector<DatasetRow> rows = ParseDatasetCsv(text, "d.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].set, PoseSet::kCalib);
  EXPECT_EQ(rows[1].set, PoseSet::kValid);
  EXPECT_EQ(rows[0].sigma_t, 0.0001);
  EXPECT_EQ(rows[0].sigma_r, 0.002);
  EXPECT_FALSE(rows[1].sigma_t.has_value());
}

std::vector<DatasetRow> RandomRows(int n, bool with_set, bool with_sigma) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<DatasetRow> rows;
  for (int i = 0; i < n; ++i) {
    DatasetRow r;
    r.pose_id = 3 * i + 1;
    r.utime = 1700000000000000 + 12345 * i;
    for (double& q : r.q) q = 3.14159 * u(rng);
    const Eigen::Vector4d wxyz = Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized();
    r.X_CT = RigidTransform::FromTranslationQuaternion({u(rng), u(rng), 1.0 + u(rng)}, wxyz);
    if (with_set) r.set = (i % 3 == 0) ? PoseSet::kValid : PoseSet::kCalib;
    if (with_sigma && i % 2 == 0) {
      r.sigma_t = 1e-4 * (1.5 + u(rng));
      r.sigma_r = 1e-3 * (1.5 + u(rng));
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(DatasetCsv, RoundTripIsExact) {
  for (const bool with_set : {false, true}) {
    for (const bool with_sigma : {false, true}) {
      const std::vector<DatasetRow> rows = RandomRows(50, with_set, with_sigma);
      const std::string text = FormatDatasetCsv(rows);
      EXPECT_EQ(text.substr(0, text.find('\n')), DatasetCsvHeader(with_set, with_sigma));
      ExpectSameRows(rows, ParseDatasetCsv(text, "mem"), 1e-15);
    }
  }
}

TEST(DatasetCsv, RoundTripThroughAFile) {
  const std::vector<DatasetRow> rows = RandomRows(10, true, true);
  const std::string path = TempPath("dataset.csv");
  WriteDatasetCsv(path, rows);
  ExpectSameRows(rows, ReadDatasetCsv(path), 1e-15);
}

TEST(DatasetCsv, HeaderAndLineForAppendingWriters) {
  EXPECT_EQ(DatasetCsvHeader(true, true), kDatasetHeader + ",set,sigma_t,sigma_r");
  DatasetRow r;
  r.pose_id = 4;
  r.utime = 9;
  r.q = {0.5, -1, 0, 0.25};
  r.X_CT = RigidTransform(Eigen::Matrix3d::Identity(), {0.1, 0, 1});
  r.set = PoseSet::kValid;
  r.sigma_t = 0.001;
  EXPECT_EQ(DatasetCsvLine(r, true, true), "4,9,0.5,-1,0,0.25,0.1,0,1,1,0,0,0,valid,0.001,");
  r.set.reset();
  EXPECT_THROW(DatasetCsvLine(r, true, false), std::invalid_argument);
}

TEST(DatasetCsvErrors, MissingColumn) {
  const std::string header = "pose_id,utime,q1,q2,q3,q4,x,y,z,qw,qx,qy";
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(header + "\n", "d.csv"); }, "d.csv", 1, "qz",
                        "missing column"));
}

// A malformed third line: the error names line 3 and the field at fault.
TEST(DatasetCsvErrors, MalformedRowIsNamedByLineAndField) {
  const std::vector<MalformedInput> rows = {
      {WithRow("1,100,0,0,0,0,0,0,1,1,0,0"), 3, "qz", "missing field"},
      {WithRow("1,100,0,0,0,0,,0,1,1,0,0,0"), 3, "x", "expected a number, got ''"},
      // not a number
      {WithRow("1,100,0,0,1.0abc,0,0,0,1,1,0,0,0"), 3, "q3", "got '1.0abc'"},
      {WithRow("1,100,0,0,0,nan,0,0,1,1,0,0,0"), 3, "q4", "got 'nan'"},
      {WithRow("1,100,0,0,0,0,0,inf,1,1,0,0,0"), 3, "y", "got 'inf'"},
      // pose_id and utime are integers
      {WithRow("1.5,100,0,0,0,0,0,0,1,1,0,0,0"), 3, "pose_id", "expected an integer"},
      {WithRow("1,1e6,0,0,0,0,0,0,1,1,0,0,0"), 3, "utime", "expected an integer"},
      // not a unit quaternion
      {WithRow("1,100,0,0,0,0,0,0,1,0.998,0,0,0"), 3, "qw,qx,qy,qz", "unit quaternion"},
      {WithRow("1,100,0,0,0,0,0,0,1,0,0,0,0"), 3, "qw,qx,qy,qz", "norm 0"},
      {WithRow("1,100,0,0,0,0,0,0,1,1e200,1e200,0,0"), 3, "qw,qx,qy,qz", "unit quaternion"},
      {WithRow("0,200,0,0,0,0,0,0,1,1,0,0,0"), 3, "pose_id",
       "duplicate pose_id 0 (first on line 2)"},
      // issue 27 point 2: a row with x or z = 1e308 read, and `analyze` printed -inf, `check`
      // inf. Translations are bounded at 10 m (the result JSON's bound), joint readings at a
      // turn (ValuesAtTheBoundsRead).
      {WithRow("1,100,0,0,0,0,1e308,0,1,1,0,0,0"), 3, "x", "within 10 m, got 1e+308"},
      {WithRow("1,100,0,0,0,0,0,0,-1e308,1,0,0,0"), 3, "z", "within 10 m"},
      {WithRow("1,100,0,0,0,0,0,10.001,1,1,0,0,0"), 3, "y", "within 10 m"},
      {WithRow("1,100,0,1e300,0,0,0,0,1,1,0,0,0"), 3, "q2", "within one turn"},
      {WithRow("1,100,0,0,0,-6.3,0,0,1,1,0,0,0"), 3, "q4", "within one turn"},
  };
  ExpectEachFailsWith(ParseDatasetCsv, "d.csv", rows);
}

// The bounds of the values beyond any robot (MalformedRowIsNamedByLineAndField) themselves read.
TEST(DatasetCsvErrors, ValuesAtTheBoundsRead) {
  EXPECT_EQ(ParseDatasetCsv(WithRow("1,100,6.28,0,0,0,10,-10,10,1,0,0,0"), "d.csv").size(), 2u);
}

TEST(DatasetCsvErrors, UnknownSet) {
  const std::string header = kDatasetHeader + ",set";
  EXPECT_TRUE(
      FailsWith([&] { ParseDatasetCsv(header + "\n1,100,0,0,0,0,0,0,1,1,0,0,0,train\n", "d.csv"); },
                "d.csv", 2, "set", "expected 'calib' or 'valid', got 'train'"));
  EXPECT_TRUE(
      FailsWith([&] { ParseDatasetCsv(header + "\n1,100,0,0,0,0,0,0,1,1,0,0,0,\n", "d.csv"); },
                "d.csv", 2, "set", "got ''"));
}

TEST(DatasetCsvErrors, NonPositiveSigma) {
  const std::string header = kDatasetHeader + ",sigma_t,sigma_r";
  EXPECT_TRUE(FailsWith(
      [&] { ParseDatasetCsv(header + "\n1,100,0,0,0,0,0,0,1,1,0,0,0,-0.001,0.01\n", "d.csv"); },
      "d.csv", 2, "sigma_t", "expected a standard deviation in"));
  EXPECT_TRUE(FailsWith(
      [&] { ParseDatasetCsv(header + "\n1,100,0,0,0,0,0,0,1,1,0,0,0,0.001,0\n", "d.csv"); },
      "d.csv", 2, "sigma_r", "expected a standard deviation in"));
}

// Regression: identify looped forever on a sigma below ~1e-154 (1/sigma^2 overflows); such
// sigmas, and absurdly large ones, are refused at load.
TEST(DatasetCsvErrors, SigmaOutsidePhysicalBounds) {
  const std::string header = kDatasetHeader + ",sigma_t,sigma_r";
  const auto row = [&](const std::string& sigmas) {
    return header + "\n1,100,0,0,0,0,0,0,1,1,0,0,0," + sigmas + "\n";
  };
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(row("1e-160,0.01"), "d.csv"); }, "d.csv", 2,
                        "sigma_t", "expected a standard deviation in [1e-09, 1] m, got 1e-160"));
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(row("1e-320,0.01"), "d.csv"); }, "d.csv", 2,
                        "sigma_t", "expected a standard deviation in"));
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(row("0.001,1e-200"), "d.csv"); }, "d.csv", 2,
                        "sigma_r", "rad"));
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(row("5,0.01"), "d.csv"); }, "d.csv", 2, "sigma_t",
                        "expected a standard deviation in"));
  EXPECT_TRUE(FailsWith([&] { ParseDatasetCsv(row("0.001,4"), "d.csv"); }, "d.csv", 2, "sigma_r",
                        "expected a standard deviation in"));
  const std::vector<DatasetRow> rows = ParseDatasetCsv(row("1e-9,3.14159"), "d.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].sigma_t, 1e-9);
}

TEST(DatasetCsvErrors, MissingFileIsNamed) {
  const std::string path = TempPath("absent.csv");
  EXPECT_TRUE(FailsWith([&] { ReadDatasetCsv(path); }, path, 0, "", "cannot open"));
}

}  // namespace
}  // namespace h4
