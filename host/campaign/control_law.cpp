// The square's control law; see control_law.h.
#include "host/campaign/control_law.h"

#include <stdexcept>

#include "host/kinematics/model31.h"

namespace h4::host {

ControlLawFunction InverseKinematicsControlLaw(std::shared_ptr<const KinematicModel> model,
                                               const std::optional<RigidTransform>& X_B31B) {
  if (model->kind() == ModelKind::k31 && !X_B31B) {
    throw std::invalid_argument(
        "a Model 31 control law needs X_B31B: the planned poses are in B, the model's in B31");
  }
  const bool in_b31 = model->kind() == ModelKind::k31;
  return
      [model, X_B31B, in_b31](const EePose& x_B, std::string* why) -> std::optional<JointVector> {
        const IkResult ik = model->InverseKinematics(in_b31 ? EePoseInB31(x_B, *X_B31B) : x_B);
        if (!ik.ok()) {
          *why = "inverse kinematics out of reach";
          return std::nullopt;
        }
        return ik.q;
      };
}

}  // namespace h4::host
