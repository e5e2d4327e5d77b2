// Tests of the square path measured by the camera (host/validation/measured_square.h) and of
// the side errors both square paths share (square_path.h, SquareErrorsOf): the measured
// analysis of what a noise-free camera would see gives the simulated run's errors; a
// placement error moves the offset, not the shape; skipped points are listed; a side
// without two points is an error naming it.
#include "host/validation/measured_square.h"

#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "host/validation/validation.h"
#include "tests/validation/validation_test_helpers.h"

namespace h4::host {
namespace {

constexpr double kTol = 1e-9;  // m

SquarePlan DefaultPlan() { return DefaultSquarePlan(); }

void ExpectSameSides(const SquareRun& a, const SquareRun& b, double tol) {
  for (size_t s = 0; s < 4; ++s) {
    EXPECT_NEAR(a.sides[s].rms, b.sides[s].rms, tol) << "side " << s + 1;
    EXPECT_NEAR(a.sides[s].max, b.sides[s].max, tol) << "side " << s + 1;
    EXPECT_NEAR(a.sides[s].shape_rms, b.sides[s].shape_rms, tol) << "side " << s + 1;
    EXPECT_NEAR(a.sides[s].shape_max, b.sides[s].shape_max, tol) << "side " << s + 1;
  }
  EXPECT_NEAR(a.shape_rms, b.shape_rms, tol);
}

TEST(SquarePlan, WritesFourSidesOfPointsFromCornerToCorner) {
  SquareOptions options;
  options.side = 0.05;
  options.points_per_side = 5;
  options.centre = Eigen::Vector3d(0.01, -0.02, -0.4);
  options.theta = 0.1;
  const auto rows = SquarePlanPoses(options, 7);
  ASSERT_EQ(rows.size(), 20u);  // each corner twice: end of a side, start of the next
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].pose_id, 7 + static_cast<int64_t>(k));
    EXPECT_DOUBLE_EQ(rows[k].theta, 0.1);
    EXPECT_DOUBLE_EQ(rows[k].Z, -0.4);
  }
  EXPECT_NEAR(rows[0].X, -0.015, 1e-15);  // corner (-,-)
  EXPECT_NEAR(rows[0].Y, -0.045, 1e-15);
  EXPECT_NEAR(rows[2].X, 0.01, 1e-15);     // middle of side 1
  EXPECT_NEAR(rows[4].X, 0.035, 1e-15);    // corner (+,-)
  EXPECT_NEAR(rows[9].Y, 0.005, 1e-15);    // corner (+,+)
  EXPECT_NEAR(rows[19].X, -0.015, 1e-15);  // back to (-,-)
  EXPECT_NEAR(rows[19].Y, -0.045, 1e-15);
}

TEST(SquarePlan, ReadsBackTheSquareAndEachPointsSide) {
  SquareOptions options;
  options.side = 0.08;
  options.points_per_side = 6;
  options.centre = Eigen::Vector3d(0.02, 0.0, -0.5);
  const SquarePlan plan = SquarePlanFromPoses(SquarePlanPoses(options, 1), "p.csv");
  EXPECT_NEAR(plan.options.side, 0.08, 1e-12);
  EXPECT_EQ(plan.options.points_per_side, 6);
  EXPECT_NEAR((plan.options.centre - options.centre).norm(), 0.0, 1e-12);
  ASSERT_EQ(plan.side.size(), 24u);
  EXPECT_EQ(plan.side[5], 0);
  EXPECT_EQ(plan.side[6], 1);
  EXPECT_EQ(plan.side[23], 3);
}

TEST(SquarePlan, RejectsRowsThatAreNotASquareInPathOrder) {
  auto rows = SquarePlanPoses(SquareOptions{}, 1001);
  std::swap(rows[3], rows[30]);
  try {
    SquarePlanFromPoses(rows, "shuffled.csv");
    FAIL() << "a shuffled plan was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shuffled.csv: row 4 (pose_id 1031)"), std::string::npos)
        << e.what();
  }
  rows.resize(10);
  EXPECT_THROW(SquarePlanFromPoses(rows, "ten.csv"), std::invalid_argument);
}

TEST(SquareErrors, KnownDisplacementGivesKnownSideErrors) {
  SquareOptions options;
  options.points_per_side = 2;
  std::vector<Eigen::Vector3d> commanded, reached;
  std::vector<int> side;
  for (const SquarePoint& p : SquarePoints(options)) {
    commanded.push_back(p.p_B);
    reached.push_back(p.p_B + Eigen::Vector3d(0.0, 0.0, 0.002));  // 2 mm below every side
    side.push_back(p.side);
  }
  // Side 2 (X = +50 mm) bulges out by 1 mm at its first point only.
  reached[2][0] += 0.001;
  const SquareRun run = SquareErrorsOf(commanded, reached, side);
  EXPECT_NEAR(run.sides[0].rms, 0.002, 1e-12);
  EXPECT_NEAR(run.sides[1].max, std::sqrt(0.002 * 0.002 + 0.001 * 0.001), 1e-12);
  EXPECT_NEAR(run.sides[1].rms, std::sqrt((0.002 * 0.002 * 2 + 0.001 * 0.001) / 2), 1e-12);
  EXPECT_NEAR(run.offset[2], 0.002, 1e-12);
  EXPECT_NEAR(run.offset[0], 0.001 / 8, 1e-12);
  EXPECT_EQ(run.sides[3].points, 2);
}

TEST(SquareErrors, ASideWithOnePointIsAnErrorNamingIt) {
  SquareOptions options;
  options.points_per_side = 3;
  std::vector<Eigen::Vector3d> commanded;
  std::vector<int> side;
  for (const SquarePoint& p : SquarePoints(options)) {
    if (p.side == 2 && !commanded.empty() && side.back() == 2) continue;  // keep one of side 3
    commanded.push_back(p.p_B);
    side.push_back(p.side);
  }
  try {
    SquareErrorsOf(commanded, commanded, side);
    FAIL() << "a side of one point was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("side 3"), std::string::npos) << e.what();
  }
}

TEST(MeasuredSquare, NoiseFreeCameraGivesTheSimulatedRunsErrors) {
  const SimulatedRobot truth = PaperTruth();
  const Model12 true_model(truth.model12);
  const Model12 apriori(PaperAprioriRobot().model12);
  const SquarePlan plan = DefaultPlan();
  for (const KinematicModel* controller : {static_cast<const KinematicModel*>(&apriori),
                                           static_cast<const KinematicModel*>(&true_model)}) {
    const SquareRun simulated =
        RunSquare(*controller, {&true_model, RigidTransform()}, plan.options);
    const MeasuredSquareRun measured = MeasuredSquareOf(
        plan, CameraSeesSquare(*controller, truth, plan), truth.X_BC, truth.X_TE, "c", "sq.csv");
    EXPECT_TRUE(measured.missing_ids.empty());
    EXPECT_EQ(measured.planned, 84u);
    ASSERT_EQ(measured.run.reached.size(), simulated.reached.size());
    ExpectSameSides(measured.run, simulated, kTol);
    EXPECT_NEAR(measured.run.rms, simulated.rms, kTol);
    EXPECT_NEAR(measured.run.mean_position_error, simulated.mean_position_error, kTol);
    EXPECT_NEAR((measured.run.offset - simulated.offset).norm(), 0.0, kTol);
  }
  // The a priori controller misses by millimetres: the comparison above is not of zeros.
  EXPECT_GT(RunSquare(apriori, {&true_model, RigidTransform()}, plan.options).rms, 1e-3);
}

/// The paper's true robot driven along the default square by the a priori Model 12
/// controller, and the rows a noise-free camera measures of it.
class CameraMeasuredSquare : public ::testing::Test {
 protected:
  const SimulatedRobot truth = PaperTruth();
  const Model12 apriori{PaperAprioriRobot().model12};
  const SquarePlan plan = DefaultPlan();
  std::vector<DatasetRow> rows = CameraSeesSquare(apriori, truth, plan);
};

TEST_F(CameraMeasuredSquare, CameraOffByOneMillimetreMovesTheOffsetNotTheShape) {
  const MeasuredSquareRun exact = MeasuredSquareOf(plan, rows, truth.X_BC, truth.X_TE, "a", "d");
  const Eigen::Vector3d shift(0.001, 0.0, 0.0);
  const RigidTransform X_BC_off(truth.X_BC.rotation(), truth.X_BC.translation() + shift);
  const MeasuredSquareRun off = MeasuredSquareOf(plan, rows, X_BC_off, truth.X_TE, "a", "d");
  EXPECT_NEAR((off.run.offset - exact.run.offset - shift).norm(), 0.0, 1e-12);
  for (size_t s = 0; s < 4; ++s) {
    EXPECT_NEAR(off.run.sides[s].shape_rms, exact.run.sides[s].shape_rms, kTol);
    EXPECT_NEAR(off.run.sides[s].shape_max, exact.run.sides[s].shape_max, kTol);
  }
  // Sides 1 and 3 run along X: a shift along X leaves their distances; 2 and 4 see it.
  EXPECT_NEAR(off.run.sides[0].rms, exact.run.sides[0].rms, kTol);
  EXPECT_NEAR(off.run.sides[2].rms, exact.run.sides[2].rms, kTol);
  EXPECT_GT(std::abs(off.run.sides[1].rms - exact.run.sides[1].rms), 1e-4);
}

TEST_F(CameraMeasuredSquare, SkippedPointsAreListedAndTheOthersMeasured) {
  const MeasuredSquareRun full = MeasuredSquareOf(plan, rows, truth.X_BC, truth.X_TE, "a", "d");
  const std::vector<int64_t> skipped = {1023, 1030, 1041};  // all on side 2
  std::erase_if(rows, [&](const DatasetRow& r) {
    return std::find(skipped.begin(), skipped.end(), r.pose_id) != skipped.end();
  });
  DatasetRow stray = rows.front();
  stray.pose_id = 5;
  rows.push_back(stray);
  const MeasuredSquareRun part = MeasuredSquareOf(plan, rows, truth.X_BC, truth.X_TE, "a", "d");
  EXPECT_EQ(part.missing_ids, skipped);
  EXPECT_EQ(part.unplanned_rows, 1u);
  EXPECT_EQ(part.run.reached.size(), 81u);
  EXPECT_EQ(part.run.sides[1].points, 18);
  EXPECT_NEAR(part.run.sides[0].rms, full.run.sides[0].rms, kTol);
  EXPECT_GT(std::abs(part.run.sides[1].rms - full.run.sides[1].rms), 1e-9);
}

TEST_F(CameraMeasuredSquare, ASideWithOneMeasuredPointIsAnErrorNamingTheSideAndDataset) {
  // Keep only the first point of side 4 (plan rows 64..84).
  std::erase_if(rows, [](const DatasetRow& r) { return r.pose_id > 1064; });
  try {
    MeasuredSquareOf(plan, rows, truth.X_BC, truth.X_TE, "a priori", "sq_apriori.csv");
    FAIL() << "a side of one point was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sq_apriori.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("side 4 of the square has 1 measured point(s) of 21"), std::string::npos)
        << what;
  }
}

TEST(Validate, MeasuredSquaresMatchTheSimulatedOnes) {
  const ValidationInputs in = WithMeasuredSquares(PaperValidationInputs());
  const ValidationReport report = Validate(in);
  ASSERT_EQ(report.measured_squares.size(), 2u);
  ASSERT_TRUE(report.models[0].square && report.models[1].square);
  ExpectSameSides(report.measured_squares[0].run, *report.models[0].square, kTol);
  ExpectSameSides(report.measured_squares[1].run, *report.models[1].square, kTol);
}

TEST(Validate, MeasuredSquaresNeedTheModel12PlacementAndThePlan) {
  ValidationInputs in = WithMeasuredSquares(PaperValidationInputs());
  ValidationInputs no_plan = in;
  no_plan.square_plan.reset();
  EXPECT_THROW(Validate(no_plan), std::invalid_argument);
  in.result31 = in.result12;
  in.result31->model = ModelKind::k31;
  in.result12.reset();
  EXPECT_TRUE(ValidateRefuses(in, "--result12")) << "measured squares without a Model 12 result";
}

}  // namespace
}  // namespace h4::host
