// The candidate set of pose planning (candidate_poses.h).
#include "host/planning/candidate_poses.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/text/invalid_reason.h"
#include "common/units.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/measurement_chain.h"
#include "host/kinematics/model12.h"
#include "host/planning/reach_check.h"

namespace h4::host {

bool CandidateOptions::IsValid(std::string* why) const {
  if (!centre.allFinite()) return Invalid(why, "centre must be finite");
  if (!half_extent.allFinite() || (half_extent.array() < 0.0).any()) {
    return Invalid(why, "half_extent must be finite and >= 0");
  }
  if (!(position_step > 1e-4)) return Invalid(why, "position_step must be > 0.1 mm");
  if ((half_extent.array() / position_step).maxCoeff() > 200.0) {
    return Invalid(why, "half_extent / position_step must be <= 200 per axis");
  }
  if (theta.empty()) return Invalid(why, "theta must hold at least one angle");
  for (double t : theta) {
    if (!std::isfinite(t) || std::abs(t) > std::numbers::pi)
      return Invalid(why, "theta must be within +-pi rad");
  }
  if (joint_range && (!joint_range->allFinite() || (*joint_range)[0] >= (*joint_range)[1])) {
    return Invalid(why, "joint_range must be finite with min < max");
  }
  if (!(image_margin_px >= 0.0)) return Invalid(why, "image_margin_px must be >= 0");
  if (!(max_tilt > 0.0 && max_tilt < std::numbers::pi / 2))
    return Invalid(why, "max_tilt must be in (0, pi/2)");
  if (!(max_theta_gain > 0.0)) return Invalid(why, "max_theta_gain must be > 0");
  if (!(min_depth > 0.0 && max_depth > min_depth)) {
    return Invalid(why, "depth range must satisfy 0 < min_depth < max_depth");
  }
  return true;
}

const char* ToString(CandidateVerdict verdict) { return kCandidateVerdictNames.NameOf(verdict); }

std::vector<Eigen::Vector3d> OuterBoardCorners(const BoardModel& board) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(INFINITY);
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-INFINITY);
  for (const Eigen::Vector3d& p_TQ : board.corners()) {
    low = low.cwiseMin(p_TQ.head<2>());
    high = high.cwiseMax(p_TQ.head<2>());
  }
  return {{low.x(), low.y(), 0.0},
          {high.x(), low.y(), 0.0},
          {high.x(), high.y(), 0.0},
          {low.x(), high.y(), 0.0}};
}

double ThetaJointGain(const KinematicModel& model, const JointVector& q, const EePose& x) {
  Eigen::Matrix4d J_x_q;
  if (!ForwardKinematicsJacobians(model, q, x, &J_x_q, nullptr)) return INFINITY;
  return J_x_q.row(3).norm();
}

CandidateFilter::CandidateFilter(const RobotDescription& robot, const CameraModel& camera,
                                 const BoardModel& board, const CandidateOptions& options)
    : robot_(robot), camera_(camera), corners_T_(board.corners()), options_(options) {
  p_TBoardCentre_ = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : OuterBoardCorners(board)) p_TBoardCentre_ += p / 4.0;
}

CandidateVerdict CandidateFilter::Check(const EePose& x_B, JointVector* joints) const {
  // Poses live in B, Model 12's base: the a priori Model 12 decides reachability (the
  // nominal Model 31 is the same geometry).
  // The robot's controller decides by the same computation (reach_check.h).
  const Model12 model(robot_.model12, robot_.assembly);
  const ReachResult reach = CheckReach(model, x_B, options_.joint_range);
  if (reach.verdict == ReachVerdict::kUnreachable) return CandidateVerdict::kUnreachable;
  if (reach.verdict == ReachVerdict::kJointRange) return CandidateVerdict::kJointRange;
  if (joints) *joints = reach.q;
  const CandidateVerdict view = CheckView(x_B);
  if (view != CandidateVerdict::kOk) return view;
  if (!(ThetaJointGain(model, reach.q, x_B) <= options_.max_theta_gain)) {
    return CandidateVerdict::kNearSingular;
  }
  return CandidateVerdict::kOk;
}

CandidateVerdict CandidateFilter::CheckView(const EePose& x_B) const {
  const RigidTransform X_CT = PredictedBoardPose(robot_.X_BC, x_B, robot_.X_TE);
  const Eigen::Vector3d p_CBoardCentre = X_CT * p_TBoardCentre_;
  if (p_CBoardCentre.z() < options_.min_depth || p_CBoardCentre.z() > options_.max_depth) {
    return CandidateVerdict::kDepth;
  }
  const Eigen::Vector3d normal_C = X_CT.rotation().col(2);
  const double cos_tilt = std::abs(normal_C.dot(p_CBoardCentre.normalized()));
  if (cos_tilt < std::cos(options_.max_tilt)) return CandidateVerdict::kTilt;
  const double margin = options_.image_margin_px;
  // Every corner, not only the outer four: the lens distortion bends the board's edges, so
  // an edge's middle can leave the image while its ends stay inside. A corner past the lens
  // model's fold projects back inside the image though the lens never shows it there.
  for (const Eigen::Vector3d& p_TQ : corners_T_) {
    Eigen::Vector2d uv;
    if (!camera_.ProjectVisible(X_CT * p_TQ, &uv)) return CandidateVerdict::kOutOfImage;
    // Pixel centres run from 0 to width - 1 (common/formats/README.md).
    if (uv.x() < margin || uv.y() < margin || uv.x() > camera_.width() - 1 - margin ||
        uv.y() > camera_.height() - 1 - margin) {
      return CandidateVerdict::kOutOfImage;
    }
  }
  return CandidateVerdict::kOk;
}

std::string CandidateSet::Summary() const {
  std::string text = fmt::format("{} candidate poses of {} examined", poses.size(), examined);
  for (size_t v = 1; v < rejected.size(); ++v) {
    if (rejected[v] > 0) {
      text += fmt::format("; {} {}", rejected[v], ToString(static_cast<CandidateVerdict>(v)));
    }
  }
  return text;
}

namespace {

// The grid values along one axis: centre + k step for |k step| <= half extent, as designed
// (to the nanometre, so plan.csv reads -0.15, not -0.15000000000000002).
std::vector<double> AxisValues(double centre, double half_extent, double step) {
  const int steps = static_cast<int>(std::floor(half_extent / step + 1e-9));
  std::vector<double> values;
  for (int k = -steps; k <= steps; ++k) values.push_back(DesignedMetres(centre + k * step));
  return values;
}

}  // namespace

CandidateSet MakeCandidateSet(const RobotDescription& robot, const CameraModel& camera,
                              const BoardModel& board, const CandidateOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("candidate options: " + why);
  const CandidateFilter filter(robot, camera, board, options);
  const double step = options.position_step;
  CandidateSet set;
  for (double z : AxisValues(options.centre.z(), options.half_extent.z(), step)) {
    for (double y : AxisValues(options.centre.y(), options.half_extent.y(), step)) {
      for (double x : AxisValues(options.centre.x(), options.half_extent.x(), step)) {
        for (double theta : options.theta) {
          CandidatePose pose;
          pose.x_B = EePose(x, y, z, theta);
          ++set.examined;
          const CandidateVerdict verdict = filter.Check(pose.x_B, &pose.q);
          if (verdict == CandidateVerdict::kOk) {
            set.poses.push_back(pose);
          } else {
            ++set.rejected[static_cast<size_t>(verdict)];
          }
        }
      }
    }
  }
  return set;
}

}  // namespace h4::host
