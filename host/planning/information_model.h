// The information a pose carries about the robot's parameters, as the measurement-space
// identification sees it (host/identification/identification_cost.h, kMeasurement): for each
// pose, the 6 rows of that cost's Jacobian (board pose error / sigma) by the free parameters,
// evaluated on the a priori robot at noise-free simulated measurements, with the parameters
// the identifiability analysis fixes removed and the columns scaled to unit norm over all
// poses (as the identification scales its Jacobian). A design (a set of poses) then has the
// information matrix M = sum of A_j^T A_j over its poses, and the covariance of the free
// parameters M^-1 in scaled units.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "host/identification/identification_cost.h"
#include "host/kinematics/kinematic_model.h"
#include "host/kinematics/model_kind.h"
#include "host/kinematics/robot_description.h"
#include "host/planning/pose_noise.h"

namespace h4::host {

struct InformationModel {
  ModelKind model = ModelKind::k31;
  std::vector<std::string> free_names;  ///< the columns, in parameter order
  std::vector<std::string> fixed;       ///< fixed by the identifiability analysis, with reasons
  /// 6 rows per pose (rotation then translation, each divided by its sigma), columns scaled.
  Eigen::MatrixXd J_scaled;
  double sigma_t = 0.0;  ///< translation std the rows are divided by, m

  int pose_count() const { return static_cast<int>(J_scaled.rows() / 6); }
  int parameter_count() const { return static_cast<int>(J_scaled.cols()); }
  /// The 6 rows of pose j.
  Eigen::Ref<const Eigen::MatrixXd> Block(int j) const { return J_scaled.middleRows(6 * j, 6); }
};

/// The information model of `poses_B` (poses in B) for a Model `kind` identification from
/// `robot` (a priori). The identifiability analysis runs over the first `analysed_count`
/// poses (the candidates; the rest, e.g. evaluation poses, do not decide what is fixed).
/// `sigmas` (one per pose, or empty): each pose's camera noise, its rows divided by it as the
/// dataset's sigma columns would be; empty: cost's default sigmas for every pose.
/// Throws std::runtime_error naming the pose when one cannot be evaluated (out of reach).
InformationModel BuildInformationModel(const RobotDescription& robot, ModelKind kind,
                                       const std::vector<EePose>& poses_B, int analysed_count,
                                       const CostOptions& cost = CostOptions{},
                                       const std::vector<PoseSigma>& sigmas = {});

/// Information matrix of the poses `chosen` (indices into the model), plus ridge * I.
Eigen::MatrixXd InformationMatrix(const InformationModel& info, const std::vector<int>& chosen,
                                  double ridge = 0.0);

/// The one-sigma board position error (m) the covariance M^-1 of a design predicts at the
/// poses `evaluated` (indices into the model), RMS over them: sigma_t times the RMS of
/// sqrt(trace(T_j M^-1 T_j^T)) with T_j the translation rows of pose j. Returns infinity
/// when M is singular (the design does not determine the parameters).
double PredictedPositionRms(const InformationModel& info, const Eigen::MatrixXd& M,
                            const std::vector<int>& evaluated);

}  // namespace h4::host
