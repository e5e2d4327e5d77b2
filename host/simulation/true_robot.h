// The simulated "true" robot: a Model 12 or Model 31 geometry and the true camera and
// board placement, drawn around an a priori description from a seed (or the paper's
// Table 2 values), so that an identification can be checked against known answers.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "common/geometry/rigid_transform.h"
#include "common/text/enum_names.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/model_kind.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// The truth. The pose plan and X_BC live in Model 12's base B; a Model 31 geometry lives
/// in B31 = NominalX_B31B(model12) * B (common/README.md's nominal map).
struct SimulatedRobot {
  /// The true Model 12 (truth_model "12"), or the a priori Model 12 that defines B and B31
  /// when the truth is a Model 31 geometry.
  Model12Parameters model12;
  /// Set when the truth is a Model 31 geometry (then the joints come from Model 31).
  std::optional<Model31Parameters> model31;
  Assembly assembly;
  RigidTransform X_BC;  ///< true camera pose in B
  RigidTransform X_TE;  ///< true end-effector pose in the board frame

  /// Model 31 when the truth has a model31 block, else Model 12.
  ModelKind truth_model() const { return model31 ? ModelKind::k31 : ModelKind::k12; }
  /// The kinematic model that generates the joints: Model31(*model31) or Model12(model12).
  std::unique_ptr<KinematicModel> MakeModel() const;
  /// X from B to the model's base frame: identity for Model 12, NominalX_B31B(model12) for 31.
  RigidTransform X_ModelB() const;
  /// The exact Model 31 of the truth in B31 (model31, or NominalModel31(model12)), with the
  /// camera in B31: what a Model 31 identification should find.
  Model31Parameters TrueModel31() const;
  RigidTransform X_B31C() const;
  /// As a robot description (robot.yaml layout): model12, model31 when set, X_BC, X_TE.
  RobotDescription Description() const;
  /// The robot a description describes, exactly: the inverse of Description().
  static SimulatedRobot FromDescription(const RobotDescription& robot);
};

enum class TrueGeometry {
  kPerturbedModel12,  ///< a priori Model 12 perturbed (h, arm, forearm, R, alpha, q0)
  kPerturbedModel31,  ///< nominal Model 31 of the a priori perturbed (P_2..4, psi, beta,
                      ///< q0, arm_i, forearm_i, h)
  kPaperTable2,       ///< Model 12 = Table 2 "Identified" rows (host/kinematics/paper_robot.h)
};
/// The names `h4cal simulate --truth-model` takes.
constexpr EnumNames<TrueGeometry, TrueGeometry::kPaperTable2> kTrueGeometryNames = {"12", "31",
                                                                                    "paper"};

/// Standard deviations of the normal perturbations from the a priori (SI). d is never
/// perturbed: it is identifiable only together with X_BC.ty.
struct PerturbationOptions {
  uint64_t seed = 1;
  double length_std = 0.002;             ///< h, arm, forearm, R / arm_i, forearm_i, h, m
  double angle_std = 0.02;               ///< alpha_i / psi_i, beta_i, rad
  double joint_offset_std = 0.04;        ///< q0_i, rad
  double base_joint_std = 0.003;         ///< P_2..P_4 coordinates (Model 31), m
  double camera_translation_std = 0.02;  ///< X_BC translation, m (centimetres)
  double camera_rotation_std = 0.035;    ///< X_BC roll, pitch, yaw, rad (~2 deg)
  double board_translation_std = 0.002;  ///< X_TE translation, m
  double board_rotation_std = 0.0087;    ///< X_TE roll, pitch, yaw, rad (~0.5 deg)
};

/// Draws the truth around `apriori` (its model12 and its X_BC, X_TE). Reproducible: the
/// same seed and options give the same robot. With kPaperTable2 only the placement is drawn.
SimulatedRobot MakeTrueRobot(const RobotDescription& apriori, TrueGeometry geometry,
                             const PerturbationOptions& options = PerturbationOptions{});

}  // namespace h4::host
