// Encoder noise seen in the corner residuals; see joint_noise.h for the model and formulas.
#include "host/identification/joint_noise.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "host/identification/identifiability.h"

namespace h4::host {
namespace {

// The sums over the poses that the expectations need.
struct JointNoiseSums {
  double projected = 0;  // sum_j |P_j r_j|^2
  double total = 0;      // |r|^2
  double trace_B = 0;    // sum_j tr(G_j^T G_j)
  int poses = 0;         // poses whose G_j has full column rank
  Eigen::MatrixXd K, M;  // n x n
};

JointNoiseSums SumOverPoses(const Eigen::VectorXd& r, const Eigen::MatrixXd& J,
                            const std::vector<PoseJointColumns>& poses) {
  JointNoiseSums s;
  s.total = r.squaredNorm();
  s.K = Eigen::MatrixXd::Zero(J.cols(), J.cols());
  s.M = s.K;
  for (const PoseJointColumns& pose : poses) {
    const Eigen::Index rows = pose.G.rows();
    if (rows < 4) continue;
    const Eigen::Matrix4d GtG = pose.G.transpose() * pose.G;
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(GtG);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-12 * GtG.trace()))
      continue;
    const Eigen::Matrix<double, 4, Eigen::Dynamic> GtJ =
        pose.G.transpose() * J.middleRows(pose.offset, rows);
    const Eigen::Vector4d Gtr = pose.G.transpose() * r.segment(pose.offset, rows);
    s.projected += Gtr.dot(ldlt.solve(Gtr));
    s.K.noalias() += GtJ.transpose() * ldlt.solve(GtJ);
    s.M.noalias() += GtJ.transpose() * GtJ;
    s.trace_B += GtG.trace();
    ++s.poses;
  }
  return s;
}

}  // namespace

JointNoise AddJointNoise(const ParameterVector& p, const Eigen::VectorXd& r,
                         const Eigen::MatrixXd& J_full,
                         const std::vector<PoseJointColumns>& poses, Uncertainty* u) {
  JointNoise out;
  if (!u->ok || !(u->sigma2 > 0)) return out;
  const Eigen::MatrixXd J = FreeColumns(J_full, p);
  const Eigen::MatrixXd A_inv = u->covariance / u->sigma2;
  const JointNoiseSums s = SumOverPoses(r, J, poses);
  // Residuals of corners given weight 0 (outliers) are exact zeros: not observations.
  const double m = static_cast<double>((r.array() != 0.0).count());
  const double n = static_cast<double>(J.cols());
  const double tr_AK = (A_inv * s.K).trace();
  const double tr_AM = (A_inv * s.M).trace();
  const double tr_AKAM = (A_inv * s.K * A_inv * s.M).trace();
  // E[projected] = s2 a1 + v b1, E[rest] = s2 a2 + v b2 (joint_noise.h); v = sigma_q^2.
  const double a1 = 4.0 * s.poses - tr_AK;
  const double b1 = s.trace_B - 2 * tr_AM + tr_AKAM;
  const double a2 = m - 4.0 * s.poses - n + tr_AK;
  const double b2 = tr_AM - tr_AKAM;
  const double rest = s.total - s.projected;
  const double det = a1 * b2 - a2 * b1;
  if (s.poses < 3 || !(a1 > 0) || !(a2 > 0) || !(b1 > 0) || det == 0) return out;
  double s2 = (s.projected * b2 - rest * b1) / det;
  double v = (a1 * rest - a2 * s.projected) / det;
  if (!(v > 0)) {  // no joint noise beyond the corners': the pixel scale alone explains r
    v = 0;
    s2 = s.total / (m - n);
  }
  out.estimated = true;
  out.sigma_q = std::sqrt(v);
  out.pixel_scale2 = s2;
  u->sigma2 = std::max(1.0, s2);
  u->covariance = u->sigma2 * A_inv + v * A_inv * s.M * A_inv;
  u->covariance = (0.5 * (u->covariance + u->covariance.transpose())).eval();
  u->std = u->covariance.diagonal().cwiseSqrt();
  u->ok = u->std.allFinite();
  return out;
}

}  // namespace h4::host
