// Fixtures of the identification tests; see identification_test_helpers.h.
#include "tests/identification/identification_test_helpers.h"

#include <stdexcept>

#include "common/geometry/rotation.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host::testing {
namespace {

RigidTransform TrueX_BC() {
  return RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.004, -0.003, -1.052),
                                            Eigen::Vector3d(0.006, -0.004, 0.012));
}

RigidTransform TrueX_TE() {
  return RigidTransform::FromTranslationRpy(Eigen::Vector3d(0.0915, 0.0887, 0.0262),
                                            Eigen::Vector3d(0.005, -0.007, 0.02));
}

}  // namespace

TrueSetup TrueModel12Setup() {
  return {std::make_unique<Model12>(kPaperIdentifiedModel12), TrueX_BC(), TrueX_TE()};
}

TrueSetup TrueModel31Setup() {
  Model31Parameters p = NominalModel31(kPaperIdentifiedModel12);
  const double mm = 1e-3, mrad = 1e-3;
  const double dP[3][3] = {{1.2, -0.8, 0.9}, {-0.7, 1.1, -1.3}, {0.6, 0.9, 1.0}};
  for (int j = 0; j < 3; ++j) {
    for (int c = 0; c < 3; ++c) p.P[static_cast<size_t>(j)][c] += dP[j][c] * mm;
  }
  const double dpsi[4] = {3, -4, 5, -2}, dbeta[4] = {-4, 3, 2, -5};
  const double darm[4] = {0.8, -0.6, 0.5, -0.9}, dforearm[4] = {-1.0, 0.7, 1.2, -0.4};
  for (size_t i = 0; i < 4; ++i) {
    p.psi[i] += dpsi[i] * mrad;
    p.beta[i] += dbeta[i] * mrad;
    p.arm[i] += darm[i] * mm;
    p.forearm[i] += dforearm[i] * mm;
  }
  p.h += 0.4 * mm;
  return {std::make_unique<Model31>(p), NominalX_B31B(kPaperIdentifiedModel12) * TrueX_BC(),
          TrueX_TE()};
}

std::vector<DatasetRow> NoiseFreeRows(const TrueSetup& setup) {
  const bool is31 = setup.model->kind() == ModelKind::k31;
  const RigidTransform X_B31B = NominalX_B31B(kPaperIdentifiedModel12);
  std::vector<DatasetRow> rows;
  for (const PlannedPose& planned : GridPosePlan()) {
    const EePose x = is31 ? EePoseInB31(planned.x, X_B31B) : planned.x;
    const IkResult ik = setup.model->InverseKinematics(x);
    if (!ik.ok()) throw std::runtime_error("test grid pose out of reach");
    DatasetRow row;
    row.pose_id = planned.pose_id;
    row.utime = 1700000000000000 + planned.pose_id;
    for (size_t i = 0; i < 4; ++i) row.q[i] = ik.q[static_cast<Eigen::Index>(i)];
    row.X_CT = PredictedBoardPose(setup.X_BC, x, setup.X_TE);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace h4::host::testing
