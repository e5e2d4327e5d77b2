// Fixtures of the validation and report tests (see validation_test_helpers.h).
#include "tests/validation/validation_test_helpers.h"

#include <stdexcept>

#include "common/units.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host {

SimulatedRobot PaperTruth() {
  return MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPaperTable2);
}

IdentificationResult PerfectModel12Result(const SimulatedRobot& truth,
                                          const std::vector<int64_t>& valid) {
  IdentificationResult result;
  result.model = ModelKind::k12;
  const Eigen::VectorXd values = Model12::ToVector(truth.model12);
  const Eigen::VectorXd apriori = Model12::ToVector(PaperAprioriRobot().model12);
  for (size_t k = 0; k < Model12::ParameterNames().size(); ++k) {
    ResultParameter p;
    p.name = Model12::ParameterNames()[k];
    p.value = values[static_cast<int>(k)];
    p.apriori = apriori[static_cast<int>(k)];
    p.std = 1e-4;
    result.parameters.push_back(p);
  }
  // The covariance whose diagonal gives each std (common/formats/README.md).
  const Eigen::Index n = static_cast<Eigen::Index>(result.parameters.size());
  result.parameter_covariance = Eigen::MatrixXd::Identity(n, n) * 1e-8;
  result.X_BC = truth.X_BC;
  result.X_TE = truth.X_TE;
  result.valid_poses = valid;
  return result;
}

ValidationInputs PaperValidationInputs() {
  const SimulatedRobot truth = PaperTruth();
  DatasetOptions options;
  options.noise = {0.0, 0.0, 0.0};
  const SimulatedDataset dataset = SimulateDataset(truth, GridPosePlan(), options);
  ValidationInputs in;
  in.apriori = PaperAprioriRobot();
  in.rows = dataset.rows;
  in.dataset_name = "paper.csv";
  std::vector<int64_t> valid;
  for (const DatasetRow& row : dataset.rows) {
    if (row.set == PoseSet::kValid) valid.push_back(row.pose_id);
  }
  in.result12 = PerfectModel12Result(truth, valid);
  for (const RulerLine& line : PaperRulerLines()) {
    in.straightness.push_back(SimulateRulerRun(truth, line, 0.0, 1));
  }
  in.truth = SimulationTruth{truth, NoiseOptions{}, 1, 1};
  return in;
}

ValidationInputs EveryPoseInTheFit() {
  ValidationInputs in = PaperValidationInputs();
  in.result12->valid_poses.clear();
  for (DatasetRow& row : in.rows) {
    row.set.reset();
    in.result12->calib_poses.push_back(row.pose_id);
  }
  in.result12->cross_validation =
      CrossValidationFigures{10, 81, 1.8734e-3, RadiansFromDegrees(0.1203), 1.1};
  return in;
}

SquarePlan DefaultSquarePlan() {
  return SquarePlanFromPoses(SquarePlanPoses(SquareOptions{}, 1001), "square.csv");
}

std::vector<DatasetRow> CameraSeesSquare(const KinematicModel& controller,
                                         const SimulatedRobot& truth, const SquarePlan& plan) {
  // By hand, not through RunSquare's code: q = IK_controller(commanded), the true robot's
  // pose FK_true(q) in B, and the true chain X_CT = inv(X_BC) * X_BE * inv(X_TE).
  const auto true_model = truth.MakeModel();
  const RigidTransform X_ModelB = truth.X_ModelB();
  std::vector<DatasetRow> rows;
  for (size_t k = 0; k < plan.commanded.size(); ++k) {
    const Eigen::Vector3d& p = plan.commanded[k];
    const EePose x(p[0], p[1], p[2], plan.options.theta);
    const IkResult ik = controller.InverseKinematics(x);
    if (!ik.ok()) throw std::invalid_argument("CameraSeesSquare: out of the controller's reach");
    const FkResult fk = ForwardKinematics(*true_model, ik.q,
                                          EePoseFromTransform(X_ModelB * TransformFromEePose(x)));
    if (!fk.ok()) throw std::invalid_argument("CameraSeesSquare: " + fk.message);
    const RigidTransform X_BE = X_ModelB.inverse() * TransformFromEePose(fk.x);
    DatasetRow row;
    row.pose_id = plan.pose_ids[k];
    row.utime = 1700000000000000 + static_cast<int64_t>(k) * 1000000;
    for (int i = 0; i < 4; ++i) row.q[static_cast<size_t>(i)] = ik.q[i];
    row.X_CT = truth.X_BC.inverse() * X_BE * truth.X_TE.inverse();
    rows.push_back(row);
  }
  return rows;
}

ValidationInputs WithMeasuredSquares(ValidationInputs in) {
  const Model12 apriori(in.apriori.model12, in.apriori.assembly);
  const Model12 identified(in.truth->robot.model12, in.truth->robot.assembly);
  in.square_plan = DefaultSquarePlan();
  in.square_measured.push_back(
      {"a priori", "sq_apriori.csv", CameraSeesSquare(apriori, in.truth->robot, *in.square_plan),
       std::nullopt});
  in.square_measured.push_back(
      {"Model 12", "sq_m12.csv", CameraSeesSquare(identified, in.truth->robot, *in.square_plan),
       ModelKind::k12});
  return in;
}

::testing::AssertionResult ValidateRefuses(const ValidationInputs& in,
                                           const std::string& expected) {
  try {
    Validate(in);
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).find(expected) != std::string::npos) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "refused without '" << expected << "': " << e.what();
  }
  return ::testing::AssertionFailure() << "accepted";
}

}  // namespace h4::host
