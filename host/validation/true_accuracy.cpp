// See true_accuracy.h.
#include "host/validation/true_accuracy.h"

#include <algorithm>
#include <cmath>

#include "host/identification/identified_robot.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model31.h"
#include "host/validation/accuracy_map.h"

namespace h4::host {

TrueAccuracy TrueAccuracyOfResult(const IdentificationResult& result, const SimulatedRobot& truth,
                                  const std::vector<EePose>& commanded_B) {
  const IdentifiedRobot identified = RebuildFromResult(result, truth.assembly);
  const std::unique_ptr<KinematicModel> true_model = truth.MakeModel();
  // The truth's model frame and the result's agree up to the rigid registration below.
  const bool in_b31 = result.model == ModelKind::k31;
  std::vector<EePose> commanded, reached;
  for (const EePose& x_B : commanded_B) {
    const EePose x = in_b31 ? EePoseInB31(x_B, truth.X_ModelB()) : x_B;
    const IkResult ik = identified.model->InverseKinematics(x);
    if (!ik.ok()) continue;
    const FkResult fk = ForwardKinematics(*true_model, ik.q, x);
    if (!fk.ok()) continue;
    commanded.push_back(x);
    reached.push_back(fk.x);
  }
  TrueAccuracy out;
  out.poses = static_cast<int>(commanded.size());
  if (out.poses == 0) return out;
  const std::vector<Eigen::Vector4d> e = ResidualAfterRigidRegistration(commanded, reached);
  double z_mean = 0, sum_sq = 0;
  for (const EePose& x : commanded) z_mean += x[2] / out.poses;
  double szz = 0, sze = 0;
  for (size_t k = 0; k < e.size(); ++k) {
    const double n2 = e[k].head<3>().squaredNorm();
    sum_sq += n2;
    out.position_max_m = std::max(out.position_max_m, std::sqrt(n2));
    const double dz = commanded[k][2] - z_mean;
    szz += dz * dz;
    sze += dz * e[k][2];
  }
  out.position_rms_m = std::sqrt(sum_sq / out.poses);
  out.z_scale_ppm = szz > 0 ? 1e6 * sze / szz : 0.0;
  return out;
}

}  // namespace h4::host
