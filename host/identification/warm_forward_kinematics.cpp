// See warm_forward_kinematics.h.
#include "host/identification/warm_forward_kinematics.h"

#include "host/kinematics/measurement_chain.h"

namespace h4::host {

FkResult WarmForwardKinematics::Solve(const KinematicModel& model, size_t j, const DatasetRow& row,
                                      const RigidTransform& X_BC, const RigidTransform& X_TE) {
  const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
  FkResult fk;
  if (has_[j]) {
    FkOptions warm;
    warm.retry_from_centre = false;  // the cold start below is the fallback
    fk = ForwardKinematics(model, q, last_[j], warm);
  }
  if (!fk.ok()) {
    // The measured pose through the chain is the natural start of Newton's method.
    const EePose guess = EePoseFromMeasurement(X_BC, row.X_CT, X_TE).x;
    fk = ForwardKinematics(model, q, guess);
  }
  has_[j] = fk.ok();
  if (fk.ok()) last_[j] = fk.x;
  return fk;
}

}  // namespace h4::host
