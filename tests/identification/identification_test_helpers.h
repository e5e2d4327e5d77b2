// Small fixtures shared by the identification tests: a "true" robot (the paper's Table 2
// identified Model 12, or a Model 31 derived from it and perturbed), a camera and board
// placement off the a priori ones, and noise-free datasets on the paper's 81-pose grid.
#pragma once

#include <memory>
#include <vector>

#include "common/geometry/rigid_transform.h"
#include "host/formats/dataset_csv.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host::testing {

struct TrueSetup {
  std::unique_ptr<KinematicModel> model;
  RigidTransform X_BC;  ///< in the model's base frame
  RigidTransform X_TE;
};

/// Table 2 "Identified" Model 12 with the camera a few mm / tenths of a degree off the paper
/// placement and the board tilted by a fraction of a degree.
TrueSetup TrueModel12Setup();
/// The nominal Model 31 of TrueModel12Setup with every joint position, axis and length
/// perturbed (mm, mrad), in B31.
TrueSetup TrueModel31Setup();

/// Noise-free rows on the paper's 81-pose grid (poses in Model 12's B; for a Model 31 setup
/// they are mapped to B31 first): q = IK(x), X_CT = inv(X_BC) X_BE inv(X_TE).
std::vector<DatasetRow> NoiseFreeRows(const TrueSetup& setup);

}  // namespace h4::host::testing
