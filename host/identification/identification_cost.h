// The identification costs (common/README.md#identification) as residual vectors with
// analytic Jacobians by the whole parameter vector (kinematic parameters, X_BC, X_TE):
//  - kJointSpace, paper eq. (3): wrap(q_i(xi, x_j) - q~_ij), x_j from the measured X_CT
//    through X_BE = X_BC X_CT X_TE, q_i by the closed-form IK (Model 12 and 31 alike);
//  - kImplicit, paper eq. (5): forearm_i - |closing vector_i| (for Model 12 too);
//  - kMeasurement: log(X_CT_measured^-1 X_CT_predicted) / sigma, six per pose, with
//    X_CT_predicted = inv(X_BC) X_BE(FK(q~)) inv(X_TE).
// The IK and FK derivatives come from the implicit function theorem on the closure
// equations f(q, x, xi) = 0 of KinematicModel.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/text/enum_names.h"
#include "common/units.h"
#include "host/formats/dataset_csv.h"
#include "host/identification/parameter_vector.h"
#include "host/identification/pose_chain.h"
#include "host/identification/warm_forward_kinematics.h"
#include "host/kinematics/kinematic_model.h"

namespace h4::host {

enum class CostKind { kJointSpace, kImplicit, kMeasurement };

/// The estimator names of IdentificationResult and of `h4cal identify --estimator`.
inline constexpr EnumNames<CostKind, CostKind::kMeasurement> kCostKindNames = {"joint", "implicit",
                                                                               "measurement"};

/// kCostKindNames' name of `kind`.
const char* ToString(CostKind kind);
/// Parses those names; nullopt when unknown.
std::optional<CostKind> ParseCostKind(const std::string& text);

struct CostOptions {
  /// Translation std of a measured X_CT when the dataset has no sigma_t, m (paper: 0.2 mm).
  double default_sigma_t = 0.2e-3;
  /// Rotation std when the dataset has no sigma_r, rad (paper: 0.03 deg).
  double default_sigma_r = RadiansFromDegrees(0.03);
  /// Use the dataset's per-pose sigma_t / sigma_r when present.
  bool use_dataset_sigmas = true;
};

class IdentificationCost {
 public:
  /// `model` gives the kind of model (it is cloned); `rows` the calibration poses.
  IdentificationCost(CostKind kind, const KinematicModel& model, std::vector<DatasetRow> rows,
                     const CostOptions& options = CostOptions{});
  IdentificationCost(const IdentificationCost& other);
  IdentificationCost& operator=(const IdentificationCost&) = delete;

  CostKind kind() const { return kind_; }
  const std::vector<DatasetRow>& rows() const { return rows_; }
  /// 4 (joint, implicit) or 6 (measurement).
  static int ResidualsPerPose(CostKind kind) { return kind == CostKind::kMeasurement ? 6 : 4; }
  int residuals_per_pose() const { return ResidualsPerPose(kind_); }
  int residual_count() const { return residuals_per_pose() * static_cast<int>(rows_.size()); }

  /// Residuals at the parameter values of `p` and, when J is non-null, their Jacobian by
  /// every parameter (residual_count x p.size()). Rows of pose j start at
  /// j * residuals_per_pose(). Returns false when a pose cannot be evaluated (IK out of
  /// reach, FK failure, singular leg); `why` then names the pose. Never returns NaN.
  /// Not const, and not thread-safe: it sets the parameters of its model copy and reuses
  /// per-pose buffers. The measurement cost starts each pose's forward kinematics from that
  /// pose's last solution (an LM step moves it little: one Newton step or none instead of
  /// several), falling back to the measured pose through the chain, the start it uses on
  /// the first call; so a result may differ from a fresh cost's in the last bits.
  bool Evaluate(const ParameterVector& p, Eigen::VectorXd* r, Eigen::MatrixXd* J,
                std::string* why = nullptr);

  /// The per-pose 1/sigma weights of the measurement cost (rotation, translation).
  double RotationWeight(const DatasetRow& row) const;
  double TranslationWeight(const DatasetRow& row) const;

 private:
  bool EvaluateJoint(const ParameterVector& p, const ChainTransforms& chain, const DatasetRow& row,
                     Eigen::Ref<Eigen::VectorXd> r, Eigen::MatrixXd* J, Eigen::Index row0,
                     std::string* why);
  bool EvaluateImplicit(const ParameterVector& p, const ChainTransforms& chain,
                        const DatasetRow& row, Eigen::Ref<Eigen::VectorXd> r, Eigen::MatrixXd* J,
                        Eigen::Index row0, std::string* why);
  bool EvaluateMeasurement(const ParameterVector& p, const ChainTransforms& chain, size_t j,
                           Eigen::Ref<Eigen::VectorXd> r, Eigen::MatrixXd* J, Eigen::Index row0,
                           std::string* why);

  CostKind kind_;
  std::unique_ptr<KinematicModel> model_;  // parameters set at each Evaluate
  std::vector<DatasetRow> rows_;
  CostOptions options_;
  std::vector<int> forearm_index_;  // per leg, index of its forearm length in xi
  // Measurement cost: the last forward kinematic solution per pose (warm start), and
  // Jacobian buffers reused across poses and calls.
  WarmForwardKinematics fk_;
  Eigen::MatrixXd J_f_xi_;
};

/// A cost by the whole parameter vector: residuals and, when J is non-null, their Jacobian
/// by every parameter (IdentificationCost::Evaluate's contract).
using ParameterCost =
    std::function<bool(const ParameterVector& p, Eigen::VectorXd* r, Eigen::MatrixXd* J)>;

/// The cost as a function of the free values alone (ParameterVector::FreeIndices order), the
/// form the minimisers take (least_squares.h ResidualFunction). The parameter vector and the
/// full Jacobian are buffers reused across evaluations (a ParameterVector copy per call costs
/// about 90 string allocations). `cost` must outlive it.
class FreeParameterResiduals {
 public:
  FreeParameterResiduals(IdentificationCost* cost, const ParameterVector& p);
  FreeParameterResiduals(ParameterCost cost, const ParameterVector& p);

  bool operator()(const Eigen::VectorXd& v, Eigen::VectorXd* r, Eigen::MatrixXd* J_free);

 private:
  ParameterCost cost_;
  std::vector<int> free_;
  ParameterVector work_;
  Eigen::VectorXd values_;
  Eigen::MatrixXd J_all_;
};

}  // namespace h4::host
