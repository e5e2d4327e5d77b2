// Forward kinematics of each calibration pose inside a cost evaluation, started from that
// pose's last solution (an LM step moves it little: one Newton step or none instead of
// several), falling back to the measured pose through the chain X_BE = X_BC X_CT X_TE,
// the start used on the first call. Shared by the measurement-space and corner costs.
#pragma once

#include <vector>

#include "host/formats/dataset_csv.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

class WarmForwardKinematics {
 public:
  explicit WarmForwardKinematics(size_t poses) : last_(poses, EePose::Zero()), has_(poses, false) {}

  /// FK of pose j (row) on `model`; a failure forgets the pose's last solution.
  FkResult Solve(const KinematicModel& model, size_t j, const DatasetRow& row,
                 const RigidTransform& X_BC, const RigidTransform& X_TE);

 private:
  std::vector<EePose> last_;
  std::vector<bool> has_;
};

}  // namespace h4::host
