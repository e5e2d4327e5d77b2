// The accuracy map (host/validation/accuracy_map.h): the first-order covariance of the pose
// the robot reaches, checked against robots drawn from the covariance and driven with the
// identified model's joints; the grid, the poses left out, the CSV and a result's map.
#include "host/validation/accuracy_map.h"

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/units.h"
#include "host/identification/identification.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/paper_robot.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

SimulatedRobot Model31Robot() {
  return MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31, {.seed = 3});
}

// A full-rank covariance with correlations: L L^T, L lower triangular with entries of
// about `scale` (m or rad).
Eigen::MatrixXd RandomCovariance(Eigen::Index n, double scale, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, scale);
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j <= i; ++j) L(i, j) = normal(rng);
  }
  return L * L.transpose();
}

// Robots drawn from N(xi_hat, C), each driven to the joints the identified model (xi_hat)
// computes for x: the spread of the poses they reach is what the map predicts.
TEST(AccuracyMapTest, PredictedSpreadMatchesRobotsDrawnFromTheCovariance) {
  const std::unique_ptr<KinematicModel> model = Model31Robot().MakeModel();
  const Eigen::VectorXd xi_hat = model->parameters();
  const Eigen::MatrixXd C = RandomCovariance(xi_hat.size(), 2e-5, 7);
  AccuracyMapOptions one_pose;
  one_pose.register_base_frame = false;  // one pose: its error is all frame motion
  one_pose.half_extent_m = 0.0;
  one_pose.z_offsets_m = {0.05};
  one_pose.theta_rad = {0.25};
  const AccuracyMap map = ComputeAccuracyMap(*model, C, one_pose);
  ASSERT_EQ(map.points.size(), 1u);
  const EePose x = map.points[0].x;
  const JointVector q = model->InverseKinematics(x).q;

  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::unique_ptr<KinematicModel> drawn = model->Clone();
  double position_sq = 0.0, theta_sq = 0.0;
  const int samples = 4000;
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd z(xi_hat.size());
    for (Eigen::Index k = 0; k < z.size(); ++k) z[k] = normal(rng);
    drawn->set_parameters(xi_hat + llt.matrixL() * z);
    const FkResult reached = ForwardKinematics(*drawn, q, x);
    ASSERT_TRUE(reached.ok()) << reached.message;
    position_sq += (reached.x - x).head<3>().squaredNorm();
    theta_sq += (reached.x[3] - x[3]) * (reached.x[3] - x[3]);
  }
  // 4000 draws: the sample variances are within about 5 % (3 sigma) of the true ones.
  EXPECT_NEAR(std::sqrt(position_sq / samples) / map.points[0].position_sigma_m, 1.0, 0.05);
  EXPECT_NEAR(std::sqrt(theta_sq / samples) / map.points[0].theta_sigma_rad, 1.0, 0.05);
  EXPECT_GT(map.points[0].position_sigma_m, 1e-6);
}

TEST(AccuracyMapTest, GridCoversXYAtEachLevelAndThetaAndScalesWithTheCovariance) {
  const std::unique_ptr<KinematicModel> model = Model31Robot().MakeModel();
  const Eigen::MatrixXd C = RandomCovariance(model->parameters().size(), 1e-5, 5);
  const AccuracyMap map = ComputeAccuracyMap(*model, C);
  // 13 x 13 X-Y positions (+-150 mm by 25 mm), 3 levels, 3 rotations.
  EXPECT_EQ(map.points.size() + static_cast<size_t>(map.left_out), 13u * 13u * 3u * 3u);
  EXPECT_GT(map.points.size(), 13u * 13u * 3u * 3u / 2);
  const AccuracyMap doubled = ComputeAccuracyMap(*model, 4.0 * C);
  ASSERT_EQ(doubled.points.size(), map.points.size());
  for (size_t i = 0; i < map.points.size(); i += 97) {
    EXPECT_NEAR(doubled.points[i].position_sigma_m, 2.0 * map.points[i].position_sigma_m, 1e-12);
  }
  EXPECT_NEAR(doubled.MedianPositionSigma(), 2.0 * map.MedianPositionSigma(), 1e-12);
  EXPECT_GE(map.MaxPositionSigma(), map.MedianPositionSigma());
}

// Errors that a rigid motion of the base frame explains vanish; what no rigid motion explains
// stays whole.
TEST(AccuracyMapTest, RegistrationTakesOutRigidMotionsOfTheBaseFrameOnly) {
  const EePose centre(0.0, 0.0, -0.45, 0.0);
  std::vector<EePose> poses;
  std::vector<Eigen::MatrixXd> rigid, bend;
  for (double x : {-0.1, 0.0, 0.1}) {
    for (double y : {-0.1, 0.1}) {
      for (double z : {-0.5, -0.4}) {
        poses.emplace_back(x, y, z, 0.2);
        // Frame shifted by (1, -2, 3) mm and turned by 0.5 mrad about Z through the centre.
        Eigen::MatrixXd e(4, 1);
        e << 1e-3 - 0.5e-3 * y, -2e-3 + 0.5e-3 * x, 3e-3, 0.5e-3;
        rigid.push_back(e);
        // A bend: Z error growing with X squared, which no rigid motion makes.
        Eigen::MatrixXd b = Eigen::MatrixXd::Zero(4, 1);
        b(2, 0) = 0.1 * (x * x - 0.02 / 3.0);
        bend.push_back(b);
      }
    }
  }
  for (const Eigen::MatrixXd& left : WithoutRigidRegistration(poses, centre, rigid)) {
    EXPECT_LT(left.norm(), 1e-12);
  }
  const std::vector<Eigen::MatrixXd> bent = WithoutRigidRegistration(poses, centre, bend);
  for (size_t k = 0; k < poses.size(); ++k) EXPECT_NEAR(bent[k](2, 0), bend[k](2, 0), 1e-12);
}

// A frame turned by 3 deg and shifted: the exact registration leaves nothing, the linear one
// (right for the map's small errors) would leave the rotation's second order, a / 2 * 3 deg
// of the poses' distance from the centre (about 0.1 mm at 0.1 m).
TEST(AccuracyMapTest, ExactRegistrationTakesOutAFrameTurnedByDegrees) {
  const double angle = RadiansFromDegrees(3.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<EePose> commanded, reached;
  std::vector<Eigen::MatrixXd> differences;
  for (double x : {-0.1, 0.0, 0.1}) {
    for (double y : {-0.1, 0.1}) {
      for (double theta : {-0.3, 0.3}) {
        const EePose c(x, y, -0.45, theta);
        EePose r;
        r.head<3>() = R * c.head<3>() + Eigen::Vector3d(0.004, -0.002, 0.001);
        r[3] = theta + angle;
        commanded.push_back(c);
        reached.push_back(r);
        differences.push_back(Eigen::MatrixXd(r - c));
      }
    }
  }
  double exact = 0.0, linear = 0.0;
  for (const Eigen::Vector4d& e : ResidualAfterRigidRegistration(commanded, reached)) {
    exact = std::max(exact, e.norm());
  }
  for (const Eigen::MatrixXd& e :
       WithoutRigidRegistration(commanded, EePose(0, 0, -0.45, 0), differences)) {
    linear = std::max(linear, e.topRows(3).norm());
  }
  EXPECT_LT(exact, 1e-12);
  EXPECT_GT(linear, 50e-6);
}

TEST(AccuracyMapTest, PosesOutOfReachAreLeftOut) {
  const std::unique_ptr<KinematicModel> model = Model31Robot().MakeModel();
  AccuracyMapOptions wide;
  wide.half_extent_m = 1.0;
  wide.step_m = 0.25;
  const AccuracyMap map =
      ComputeAccuracyMap(*model, Eigen::MatrixXd::Identity(31, 31) * 1e-10, wide);
  EXPECT_GT(map.left_out, 0);
  EXPECT_GT(map.points.size(), 0u);
  for (const AccuracyMapPoint& point : map.points) {
    EXPECT_TRUE(model->InverseKinematics(point.x).ok());
  }
}

// issue 27 point 1: a covariance beyond what a double holds gave sigmas of inf; the report
// printed "median inf mm" and passed inf to gnuplot. Such poses are left out.
TEST(AccuracyMapTest, PosesWithoutAFiniteSigmaAreLeftOut) {
  const std::unique_ptr<KinematicModel> model = Model31Robot().MakeModel();
  const AccuracyMap map = ComputeAccuracyMap(*model, Eigen::MatrixXd::Identity(31, 31) * 1e308);
  EXPECT_GT(map.left_out, 0);
  for (const AccuracyMapPoint& point : map.points) {
    EXPECT_TRUE(std::isfinite(point.position_sigma_m) && std::isfinite(point.theta_sigma_rad));
  }
  EXPECT_TRUE(std::isfinite(map.MedianPositionSigma()));
  EXPECT_EQ(AccuracyMapCsv(map).find("inf"), std::string::npos);
}

TEST(AccuracyMapTest, RefusesBadOptionsAndAWronglySizedCovariance) {
  const std::unique_ptr<KinematicModel> model = Model31Robot().MakeModel();
  AccuracyMapOptions bad;
  bad.step_m = 0.0;
  EXPECT_THROW(ComputeAccuracyMap(*model, Eigen::MatrixXd::Zero(31, 31), bad),
               std::invalid_argument);
  bad = AccuracyMapOptions{};
  bad.theta_rad.clear();
  EXPECT_THROW(ComputeAccuracyMap(*model, Eigen::MatrixXd::Zero(31, 31), bad),
               std::invalid_argument);
  EXPECT_THROW(ComputeAccuracyMap(*model, Eigen::MatrixXd::Zero(13, 13)), std::invalid_argument);
}

// The map of an identified result: from its parameter covariance; the CSV has a row per
// reachable pose; a result without a covariance has no map.
TEST(AccuracyMapTest, AResultsMapComesFromItsParameterCovarianceAndWritesCsv) {
  PerturbationOptions perturbation;
  perturbation.seed = 2;
  const SimulatedRobot truth =
      MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel12, perturbation);
  DatasetOptions data;
  data.seed = 2;
  const IdentificationOutcome out =
      IdentifyRobot(PaperAprioriRobot(), ModelKind::k12,
                    SimulateDataset(truth, GridPosePlan(), data).rows, IdentificationOptions{});
  ASSERT_TRUE(out.result.parameter_covariance.has_value());
  const std::optional<AccuracyMap> map = AccuracyMapOfResult(out.result, truth.assembly);
  ASSERT_TRUE(map.has_value());
  EXPECT_EQ(map->model, ModelKind::k12);
  // 0.2 mm camera noise, 81 poses: the calibrated robot is good to tenths of a millimetre.
  EXPECT_GT(map->MedianPositionSigma(), 0.005e-3);
  EXPECT_LT(map->MedianPositionSigma(), 0.5e-3);

  std::istringstream csv(AccuracyMapCsv(*map));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "X,Y,Z,theta,position_sigma,theta_sigma");
  size_t rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, map->points.size());

  IdentificationResult without = out.result;
  without.parameter_covariance.reset();
  EXPECT_FALSE(AccuracyMapOfResult(without, truth.assembly).has_value());
}

}  // namespace
}  // namespace h4::host
