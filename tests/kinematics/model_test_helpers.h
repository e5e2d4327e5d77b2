// Test helpers shared by the tests of Model 12 and Model 31: their parameter vectors (in the
// order of common/README.md#model-12-design-model-12-parameters and
// common/README.md#model-31-calibration-model-31-parameters: the names at given places,
// set_parameters taking a vector back whole and refusing one of the wrong size) and their
// constraint Jacobians checked at the same poses.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "host/kinematics/kinematic_model.h"
#include "tests/kinematics/jacobian_check_helpers.h"

namespace h4::host::testing {

/// Expects `model` to have `count` parameters, with each (index, name) of `names_at` in place.
/// Wrap in ASSERT_NO_FATAL_FAILURE before indexing the parameters: a wrong count stops here.
inline void ExpectParameterNames(const KinematicModel& model, size_t count,
                                 const std::vector<std::pair<size_t, std::string>>& names_at) {
  const std::vector<std::string>& names = model.parameter_names();
  ASSERT_EQ(names.size(), count);
  for (const auto& [index, name] : names_at) EXPECT_EQ(names[index], name) << "parameter " << index;
}

/// Expects `other`, a model of the same kind, to take `xi` whole through set_parameters and to
/// refuse a vector of `wrong_size` parameters.
inline void ExpectSetParametersTakesXiAndRefusesWrongSize(KinematicModel& other,
                                                          const Eigen::VectorXd& xi,
                                                          Eigen::Index wrong_size) {
  other.set_parameters(xi);
  EXPECT_EQ(other.parameters(), xi);
  EXPECT_THROW(other.set_parameters(Eigen::VectorXd::Zero(wrong_size)), std::invalid_argument);
}

/// The poses (in the base frame B) at which the models' constraint Jacobians are checked.
inline std::vector<EePose> JacobianCheckPoses() {
  return {EePose(0.0, 0.0, -0.45, 0.0), EePose(0.1, -0.1, -0.375, 0.349),
          EePose(-0.08, 0.06, -0.52, -0.3)};
}

/// Closes the legs of `model` at `x`, moves the joints by `dq` off the closure manifold (the
/// Jacobians of f hold everywhere) and expects ConstraintJacobiansMatchFiniteDifferences
/// there; `q`, when given, receives the joints checked. Wrap in ASSERT_NO_FATAL_FAILURE when
/// more follows: a pose the model cannot reach stops here.
inline void ExpectConstraintJacobiansMatchOffTheManifold(const KinematicModel& model,
                                                         const EePose& x, const JointVector& dq,
                                                         JointVector* q = nullptr) {
  const IkResult ik = model.InverseKinematics(x);
  ASSERT_TRUE(ik.ok());
  const JointVector q_checked = ik.q + dq;
  EXPECT_TRUE(ConstraintJacobiansMatchFiniteDifferences(model, q_checked, x));
  if (q) *q = q_checked;
}

}  // namespace h4::host::testing
