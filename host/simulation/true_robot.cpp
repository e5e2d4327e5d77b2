// The simulated true robot; see true_robot.h.
#include "host/simulation/true_robot.h"

#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/simulation/deviation_draw.h"

namespace h4::host {

std::unique_ptr<KinematicModel> SimulatedRobot::MakeModel() const {
  if (model31) return std::make_unique<Model31>(*model31, assembly);
  return std::make_unique<Model12>(model12, assembly);
}

RigidTransform SimulatedRobot::X_ModelB() const {
  return model31 ? NominalX_B31B(model12) : RigidTransform();
}

Model31Parameters SimulatedRobot::TrueModel31() const {
  return model31 ? *model31 : NominalModel31(model12);
}

RigidTransform SimulatedRobot::X_B31C() const { return NominalX_B31B(model12) * X_BC; }

RobotDescription SimulatedRobot::Description() const {
  RobotDescription robot;
  robot.model12 = model12;
  robot.model31 = model31;
  robot.assembly = assembly;
  robot.X_BC = X_BC;
  robot.X_TE = X_TE;
  return robot;
}

SimulatedRobot SimulatedRobot::FromDescription(const RobotDescription& robot) {
  return {.model12 = robot.model12,
          .model31 = robot.model31,
          .assembly = robot.assembly,
          .X_BC = robot.X_BC,
          .X_TE = robot.X_TE};
}

SimulatedRobot MakeTrueRobot(const RobotDescription& apriori, TrueGeometry geometry,
                             const PerturbationOptions& o) {
  NormalDeviationDraw draw(o.seed);
  SimulatedRobot truth;
  truth.assembly = apriori.assembly;
  truth.model12 = apriori.model12;
  // The draw order is fixed (placement first) so a seed means the same placement whatever
  // the geometry.
  truth.X_BC = draw.Placement(apriori.X_BC, o.camera_translation_std, o.camera_rotation_std);
  truth.X_TE = draw.Placement(apriori.X_TE, o.board_translation_std, o.board_rotation_std);
  switch (geometry) {
    case TrueGeometry::kPaperTable2:
      truth.model12 = kPaperIdentifiedModel12;
      truth.model12.d = apriori.model12.d;
      break;
    case TrueGeometry::kPerturbedModel12: {
      Model12Parameters& p = truth.model12;
      p.h = draw(p.h, o.length_std);
      p.arm = draw(p.arm, o.length_std);
      p.forearm = draw(p.forearm, o.length_std);
      p.R = draw(p.R, o.length_std);
      for (double& alpha : p.alpha) alpha = draw(alpha, o.angle_std);
      for (double& q0 : p.q0) q0 = draw(q0, o.joint_offset_std);
      break;
    }
    case TrueGeometry::kPerturbedModel31: {
      Model31Parameters p = NominalModel31(apriori.model12);
      for (Eigen::Vector3d& P : p.P) {
        for (int k = 0; k < 3; ++k) P[k] = draw(P[k], o.base_joint_std);
      }
      for (double& psi : p.psi) psi = draw(psi, o.angle_std);
      for (double& beta : p.beta) beta = draw(beta, o.angle_std);
      for (double& q0 : p.q0) q0 = draw(q0, o.joint_offset_std);
      for (double& arm : p.arm) arm = draw(arm, o.length_std);
      for (double& forearm : p.forearm) forearm = draw(forearm, o.length_std);
      p.h = draw(p.h, o.length_std);
      truth.model31 = p;
      break;
    }
  }
  return truth;
}

}  // namespace h4::host
