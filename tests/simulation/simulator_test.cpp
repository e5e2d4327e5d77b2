// Tests of the simulator library: true robots drawn from a seed, simulated datasets
// (reproducible, exact without noise, noise statistics as configured, 71/10 split), and
// the truth file.
#include <cmath>

#include <gtest/gtest.h>

#include "common/formats/format_error.h"
#include "common/geometry/rotation.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"
#include "host/simulation/truth_file.h"

namespace h4::host {
namespace {

DatasetOptions NoiseFree(uint64_t seed) {
  DatasetOptions options;
  options.seed = seed;
  options.noise = {0.0, 0.0, 0.0};
  return options;
}

TEST(TrueRobot, SameSeedGivesSameRobotAndOtherSeedAnother) {
  const RobotDescription apriori = PaperAprioriRobot();
  PerturbationOptions options;
  options.seed = 5;
  const SimulatedRobot a = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31, options);
  const SimulatedRobot b = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31, options);
  options.seed = 6;
  const SimulatedRobot c = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31, options);
  ASSERT_TRUE(a.model31 && b.model31 && c.model31);
  EXPECT_EQ(Model31::ToVector(*a.model31), Model31::ToVector(*b.model31));
  EXPECT_TRUE(a.X_BC.IsNearlyEqualTo(b.X_BC, 0.0, 0.0));
  EXPECT_GT((Model31::ToVector(*a.model31) - Model31::ToVector(*c.model31)).norm(), 1e-3);
  EXPECT_EQ(a.truth_model(), ModelKind::k31);
}

TEST(TrueRobot, PerturbationsHaveTheConfiguredSize) {
  const RobotDescription apriori = PaperAprioriRobot();
  PerturbationOptions options;
  options.seed = 11;
  const SimulatedRobot truth = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31, options);
  const Eigen::VectorXd delta =
      Model31::ToVector(*truth.model31) - Model31::ToVector(NominalModel31(apriori.model12));
  EXPECT_GT(delta.segment<9>(0).cwiseAbs().maxCoeff(), 0.2 * options.base_joint_std);
  EXPECT_LT(delta.segment<9>(0).cwiseAbs().maxCoeff(), 5.0 * options.base_joint_std);
  EXPECT_LT(delta.segment<8>(9).cwiseAbs().maxCoeff(), 5.0 * options.angle_std);
  EXPECT_EQ(delta[30], 0.0) << "d is not perturbed";
  const double camera_offset = (truth.X_BC.translation() - apriori.X_BC.translation()).norm();
  EXPECT_GT(camera_offset, 0.002);
  EXPECT_LT(camera_offset, 0.1);
  const double camera_angle =
      So3Log(apriori.X_BC.rotation().transpose() * truth.X_BC.rotation()).norm();
  EXPECT_GT(camera_angle, 0.2 * options.camera_rotation_std);
  EXPECT_LT(camera_angle, 5.0 * options.camera_rotation_std);
}

TEST(TrueRobot, PaperGeometryIsTable2Identified) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  EXPECT_FALSE(truth.model31.has_value());
  EXPECT_DOUBLE_EQ(truth.model12.forearm, 0.4876);
  EXPECT_DOUBLE_EQ(truth.model12.alpha[1], 3.1016);
  EXPECT_DOUBLE_EQ(truth.model12.q0[3], -0.0561);
}

TEST(DatasetSimulator, BoardFacesTheCameraAtHalfAMetre) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  const SimulatedDataset data = SimulateDataset(truth, GridPosePlan(), NoiseFree(1));
  ASSERT_EQ(data.rows.size(), 81u);
  for (const SimulatedPose& pose : data.truth) {
    EXPECT_GT(pose.X_CT.translation().z(), 0.45) << "pose " << pose.pose_id;
    EXPECT_LT(pose.X_CT.translation().z(), 0.70) << "pose " << pose.pose_id;
    // z_T (away from the printed face) along z_C: the printed face looks at the camera.
    EXPECT_GT(pose.X_CT.rotation()(2, 2), 0.99) << "pose " << pose.pose_id;
  }
}

TEST(DatasetSimulator, SameSeedGivesSameDataset) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel12);
  DatasetOptions options;
  options.seed = 42;
  const SimulatedDataset a = SimulateDataset(truth, GridPosePlan(), options);
  const SimulatedDataset b = SimulateDataset(truth, GridPosePlan(), options);
  options.seed = 43;
  const SimulatedDataset c = SimulateDataset(truth, GridPosePlan(), options);
  EXPECT_EQ(FormatDatasetCsv(a.rows), FormatDatasetCsv(b.rows));
  EXPECT_NE(FormatDatasetCsv(a.rows), FormatDatasetCsv(c.rows));
}

TEST(DatasetSimulator, SplitsInto71CalibAnd10ValidBySeed) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  auto valid_ids = [&](uint64_t seed) {
    DatasetOptions options;
    options.seed = seed;
    std::vector<int64_t> ids;
    int calib = 0;
    for (const DatasetRow& row : SimulateDataset(truth, GridPosePlan(), options).rows) {
      EXPECT_TRUE(row.set.has_value());
      if (row.set == PoseSet::kValid) ids.push_back(row.pose_id);
      if (row.set == PoseSet::kCalib) ++calib;
      EXPECT_EQ(row.sigma_t, options.noise.sigma_t);
      EXPECT_EQ(row.sigma_r, options.noise.sigma_r);
    }
    EXPECT_EQ(calib, 71);
    return ids;
  };
  const std::vector<int64_t> a = valid_ids(3), b = valid_ids(3), c = valid_ids(4);
  EXPECT_EQ(a.size(), 10u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

void ExpectNoiseFreeDataSatisfiesConstraints(const SimulatedRobot& truth) {
  const auto model = truth.MakeModel();
  const SimulatedDataset data = SimulateDataset(truth, GridPosePlan(), NoiseFree(9));
  ASSERT_EQ(data.rows.size(), 81u);
  for (size_t k = 0; k < data.rows.size(); ++k) {
    const DatasetRow& row = data.rows[k];
    const MeasuredEePose measured = EePoseFromMeasurement(truth.X_BC, row.X_CT, truth.X_TE);
    EXPECT_LT(measured.tilt_angle, 1e-12);
    EXPECT_LT((measured.x - data.truth[k].x_B).norm(), 1e-12);
    const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
    const EePose x = EePoseInB31(measured.x, truth.X_ModelB());
    EXPECT_LT(model->Constraints(q, x).cwiseAbs().maxCoeff(), 1e-12) << "pose " << row.pose_id;
  }
}

TEST(DatasetSimulator, NoiseFreeModel12DataSatisfiesTheConstraints) {
  ExpectNoiseFreeDataSatisfiesConstraints(
      MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel12));
}

TEST(DatasetSimulator, NoiseFreeModel31DataSatisfiesTheConstraints) {
  ExpectNoiseFreeDataSatisfiesConstraints(
      MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31));
}

TEST(DatasetSimulator, NoiseStatisticsMatchTheSettings) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31);
  PosePlan plan;
  for (int repeat = 0; repeat < 20; ++repeat) {
    for (PlannedPose pose : GridPosePlan()) {
      pose.pose_id += 1000 * repeat;
      plan.push_back(pose);
    }
  }
  DatasetOptions options;
  options.seed = 77;
  const SimulatedDataset data = SimulateDataset(truth, plan, options);
  ASSERT_EQ(data.rows.size(), plan.size());
  Eigen::Array3d sum_t = Eigen::Array3d::Zero(), sq_t = sum_t, sum_r = sum_t, sq_r = sum_t;
  double sum_q = 0.0, sq_q = 0.0;
  for (size_t k = 0; k < data.rows.size(); ++k) {
    const DatasetRow& row = data.rows[k];
    const SimulatedPose& pose = data.truth[k];
    const Eigen::Array3d dt = row.X_CT.translation() - pose.X_CT.translation();
    const Eigen::Array3d dr = So3Log(pose.X_CT.rotation().transpose() * row.X_CT.rotation());
    sum_t += dt;
    sq_t += dt * dt;
    sum_r += dr;
    sq_r += dr * dr;
    for (int i = 0; i < 4; ++i) {
      const double dq = WrapAngle(row.q[static_cast<size_t>(i)] - pose.q[i]);
      sum_q += dq;
      sq_q += dq * dq;
    }
  }
  const double n = static_cast<double>(data.rows.size());
  const NoiseOptions& noise = options.noise;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(std::sqrt(sq_t[k] / n), noise.sigma_t, 0.05 * noise.sigma_t) << "axis " << k;
    EXPECT_NEAR(sum_t[k] / n, 0.0, 5.0 * noise.sigma_t / std::sqrt(n)) << "axis " << k;
    EXPECT_NEAR(std::sqrt(sq_r[k] / n), noise.sigma_r, 0.05 * noise.sigma_r) << "axis " << k;
    EXPECT_NEAR(sum_r[k] / n, 0.0, 5.0 * noise.sigma_r / std::sqrt(n)) << "axis " << k;
  }
  EXPECT_NEAR(std::sqrt(sq_q / (4 * n)), noise.sigma_q, 0.05 * noise.sigma_q);
  EXPECT_NEAR(sum_q / (4 * n), 0.0, 5.0 * noise.sigma_q / std::sqrt(4 * n));
}

TEST(DatasetSimulator, ListsUnreachablePosesInsteadOfFailing) {
  const SimulatedRobot truth = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  PosePlan plan = GridPosePlan();
  plan.push_back({500, EePose(0.0, 0.0, -2.0, 0.0)});
  const SimulatedDataset data = SimulateDataset(truth, plan);
  EXPECT_EQ(data.rows.size(), 81u);
  ASSERT_EQ(data.unreachable.size(), 1u);
  EXPECT_EQ(data.unreachable[0], 500);
}

TEST(TruthFile, RoundTripsAndReadsAsARobotDescription) {
  PerturbationOptions perturbation;
  perturbation.seed = 21;
  SimulationTruth truth;
  truth.robot = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31, perturbation);
  truth.robot_seed = 21;
  truth.dataset_seed = 22;
  const std::string text = FormatTruthYaml(truth);
  const SimulationTruth back = ParseTruthYaml(text, "truth.yaml");
  ASSERT_TRUE(back.robot.model31.has_value());
  EXPECT_EQ(Model31::ToVector(*back.robot.model31), Model31::ToVector(*truth.robot.model31));
  EXPECT_TRUE(back.robot.X_BC.IsNearlyEqualTo(truth.robot.X_BC, 1e-15, 1e-15));
  EXPECT_TRUE(back.robot.X_TE.IsNearlyEqualTo(truth.robot.X_TE, 1e-15, 1e-15));
  EXPECT_EQ(back.noise.sigma_r, truth.noise.sigma_r);
  EXPECT_EQ(back.dataset_seed, 22u);
  EXPECT_NE(text.find("X_B31C"), std::string::npos);
  const RobotDescription robot = ParseRobotYaml(text, "truth.yaml");
  EXPECT_EQ(Model31::ToVector(Model31Of(robot)), Model31::ToVector(*truth.robot.model31));
}

TEST(TruthFile, RejectsModel31TruthWithoutGeometry) {
  SimulationTruth truth;
  truth.robot = MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
  std::string text = FormatTruthYaml(truth);
  const auto at = text.find("truth_model: \"12\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "truth_model: \"31\"");
  EXPECT_THROW(ParseTruthYaml(text, "truth.yaml"), FormatError);
}

}  // namespace
}  // namespace h4::host
