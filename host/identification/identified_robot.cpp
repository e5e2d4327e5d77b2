// Identified robot rebuilt from a result, and its figures on a dataset; see identified_robot.h.
#include "host/identification/identified_robot.h"

#include <cmath>
#include <stdexcept>

#include "common/geometry/rotation.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host {

IdentifiedRobot RebuildFromResult(const IdentificationResult& result, const Assembly& assembly) {
  IdentifiedRobot robot;
  if (result.model == ModelKind::k12) {
    robot.model = std::make_unique<Model12>(Model12Parameters{}, assembly);
  } else {
    robot.model = std::make_unique<Model31>(Model31Parameters{}, assembly);
  }
  const std::vector<std::string>& names = robot.model->parameter_names();
  Eigen::VectorXd xi(static_cast<Eigen::Index>(names.size()));
  for (size_t k = 0; k < names.size(); ++k) {
    const ResultParameter* p = result.Find(names[k]);
    if (p == nullptr) {
      throw std::invalid_argument("identification result: " + ModelLabel(result.model) +
                                  " parameter \"" + names[k] + "\" is missing");
    }
    xi[static_cast<Eigen::Index>(k)] = p->value;
  }
  robot.model->set_parameters(xi);
  robot.X_BC = result.X_BC;
  robot.X_TE = result.X_TE;
  return robot;
}

RigidTransform CameraInPlanFrame(const IdentificationResult& result,
                                 const Model12Parameters& apriori) {
  if (result.model == ModelKind::k12) return result.X_BC;
  return NominalX_B31B(apriori).inverse() * result.X_BC;
}

void RequireModel12Result(const IdentificationResult& result, const std::string& source,
                          const std::string& use) {
  if (result.model == ModelKind::k12) return;
  throw std::invalid_argument((source.empty() ? "" : source + ": ") + use +
                              " needs a Model 12 result, this is " + ModelLabel(result.model));
}

std::optional<RigidTransform> PredictBoardPose(const KinematicModel& model,
                                               const RigidTransform& X_BC,
                                               const RigidTransform& X_TE, const JointVector& q,
                                               const std::optional<EePose>& guess) {
  const FkResult fk = ForwardKinematics(model, q, guess);
  if (!fk.ok()) return std::nullopt;
  return PredictedBoardPose(X_BC, fk.x, X_TE);
}

std::array<double, 4> JointResidualRms(const KinematicModel& model, const RigidTransform& X_BC,
                                       const RigidTransform& X_TE,
                                       const std::vector<DatasetRow>& rows, int* unreachable) {
  std::array<double, 4> sum{};
  int used = 0, out_of_reach = 0;
  for (const DatasetRow& row : rows) {
    const IkResult ik = model.InverseKinematics(EePoseFromMeasurement(X_BC, row.X_CT, X_TE).x);
    if (!ik.ok()) {
      ++out_of_reach;
      continue;
    }
    for (size_t i = 0; i < 4; ++i) {
      const double e = WrapAngle(ik.q[static_cast<Eigen::Index>(i)] - row.q[i]);
      sum[i] += e * e;
    }
    ++used;
  }
  if (unreachable != nullptr) *unreachable = out_of_reach;
  std::array<double, 4> rms{};
  for (size_t i = 0; i < 4; ++i) rms[i] = used > 0 ? std::sqrt(sum[i] / used) : 0.0;
  return rms;
}

BoardPoseErrors BoardPoseErrorsOf(const KinematicModel& model, const RigidTransform& X_BC,
                                  const RigidTransform& X_TE, const std::vector<DatasetRow>& rows) {
  BoardPoseErrors out;
  double sum_p = 0.0, sum_r = 0.0;
  for (const DatasetRow& row : rows) {
    const JointVector q(row.q[0], row.q[1], row.q[2], row.q[3]);
    // The measured pose through the chain is a good start for Newton's method.
    const EePose guess = EePoseFromMeasurement(X_BC, row.X_CT, X_TE).x;
    const std::optional<RigidTransform> X_CT = PredictBoardPose(model, X_BC, X_TE, q, guess);
    if (!X_CT) {
      ++out.failed;
      continue;
    }
    const Eigen::Matrix<double, 6, 1> e = PoseError(row.X_CT, *X_CT);
    sum_r += e.head<3>().squaredNorm();
    sum_p += e.tail<3>().squaredNorm();
    ++out.poses;
  }
  if (out.poses > 0) {
    out.position_rms = std::sqrt(sum_p / out.poses);
    out.rotation_rms = std::sqrt(sum_r / out.poses);
  }
  return out;
}

Eigen::MatrixXd ResultCovarianceFor(const IdentificationResult& result, const ParameterVector& p,
                                    bool* with_correlations) {
  // index_in_result[i]: the row of p's parameter i in the result's list, or -1.
  std::vector<Eigen::Index> index_in_result(static_cast<size_t>(p.size()), -1);
  for (size_t k = 0; k < result.parameters.size(); ++k) {
    for (int i = 0; i < p.size(); ++i) {
      if (p.names()[static_cast<size_t>(i)] == result.parameters[k].name) {
        index_in_result[static_cast<size_t>(i)] = static_cast<Eigen::Index>(k);
      }
    }
  }
  if (with_correlations) *with_correlations = result.parameter_covariance.has_value();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(p.size(), p.size());
  for (int a = 0; a < p.size(); ++a) {
    const Eigen::Index ka = index_in_result[static_cast<size_t>(a)];
    if (ka < 0) continue;
    if (!result.parameter_covariance) {
      const double sigma = result.parameters[static_cast<size_t>(ka)].std.value_or(0.0);
      C(a, a) = sigma * sigma;
      continue;
    }
    for (int b = 0; b < p.size(); ++b) {
      const Eigen::Index kb = index_in_result[static_cast<size_t>(b)];
      if (kb >= 0) C(a, b) = (*result.parameter_covariance)(ka, kb);
    }
  }
  return C;
}

}  // namespace h4::host
