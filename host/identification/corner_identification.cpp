// The corner path; see corner_identification.h.
#include "host/identification/corner_identification.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "host/identification/camera_parameters.h"
#include "host/identification/identification_cost.h"
#include "host/identification/robot_accuracy.h"
#include "host/identification/verdict.h"

namespace h4::host {
namespace {

// Weighted residual RMS per axis in px: the weights are 1/sigma, so divide them out.
double PixelRms(const CornerCost& cost, const Eigen::VectorXd& r) {
  double sum = 0;
  int n = 0;
  for (size_t j = 0; j < cost.corners().size(); ++j) {
    const PoseCorners& c = cost.corners()[j];
    for (size_t k = 0; k < c.uv.size(); ++k) {
      if (c.weight[k] == 0) continue;
      sum += r.segment<2>(cost.pose_offset(j) + 2 * static_cast<Eigen::Index>(k)).squaredNorm() /
             (c.weight[k] * c.weight[k]);
      n += 2;
    }
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

// Per-corner outliers: squared normalised residual over the campaign's robust scale (the
// median of chi-square(2) is 2 ln 2). Returns how many were newly given weight 0.
int RejectCornerOutliers(CornerCost* cost, const Eigen::VectorXd& r, double limit) {
  std::vector<double> d2;
  for (size_t j = 0; j < cost->corners().size(); ++j) {
    const PoseCorners& c = cost->corners()[j];
    for (size_t k = 0; k < c.uv.size(); ++k) {
      if (c.weight[k] == 0) continue;
      d2.push_back(
          r.segment<2>(cost->pose_offset(j) + 2 * static_cast<Eigen::Index>(k)).squaredNorm());
    }
  }
  if (d2.empty()) return 0;
  std::vector<double> sorted = d2;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double scale = std::max(sorted[sorted.size() / 2] / (2 * std::log(2.0)), 1e-12);
  int rejected = 0;
  std::vector<PoseCorners>& all = *cost->mutable_corners();
  for (size_t j = 0; j < all.size(); ++j) {
    PoseCorners& c = all[j];
    for (size_t k = 0; k < c.uv.size(); ++k) {
      if (c.weight[k] == 0) continue;
      const double e2 =
          r.segment<2>(cost->pose_offset(j) + 2 * static_cast<Eigen::Index>(k)).squaredNorm();
      if (e2 > limit * scale) {
        c.weight[k] = 0;
        ++rejected;
      }
    }
  }
  return rejected;
}

ParameterVector WithCameraBlock(const ParameterVector& start, const CameraIntrinsics& camera,
                                const std::string& fixed_reason) {
  ParameterVector p = start;
  p.AppendCameraBlock(CameraParameterNames(camera), CameraParameterValues(camera));
  if (!fixed_reason.empty()) {
    for (int i = p.camera_offset(); i < p.size(); ++i) p.Fix(i, fixed_reason);
  }
  return p;
}

}  // namespace

std::vector<PoseCorners> GroupCornersByRow(const std::vector<DatasetRow>& rows,
                                           const std::vector<CornerObservation>& corners,
                                           const BoardModel& board, double default_sigma_px) {
  std::map<int64_t, size_t> row_of;
  for (size_t j = 0; j < rows.size(); ++j) row_of[rows[j].pose_id] = j;
  std::vector<PoseCorners> grouped(rows.size());
  for (const CornerObservation& c : corners) {
    const auto it = row_of.find(c.pose_id);
    if (it == row_of.end()) continue;
    // Where the corners meet the board: the corner id and its tag id both of this board
    // (a tag id 99 on a 36-tag board, 7 for corner 4, a tag id on a chessboard: issue 42).
    if (const std::string problem = board.CornerTagProblem(c.tag_id, c.corner); !problem.empty()) {
      throw std::invalid_argument(fmt::format("pose {}: {}", c.pose_id, problem));
    }
    const std::optional<Eigen::Vector3d> p_TQ = board.Corner(c.corner);
    PoseCorners& g = grouped[it->second];
    g.p_TQ.push_back(*p_TQ);
    g.uv.emplace_back(c.u, c.v);
    g.weight.push_back(1.0 / c.sigma_px.value_or(default_sigma_px));
  }
  return grouped;
}

void RequireCornersOfDataset(const std::vector<DatasetRow>& rows,
                             const std::vector<CornerObservation>& corners,
                             const std::string& corners_name) {
  std::set<int64_t> pose_ids;
  for (const DatasetRow& row : rows) pose_ids.insert(row.pose_id);
  if (corners.empty() || rows.empty()) return;
  int64_t low = corners.front().pose_id, high = low;
  for (const CornerObservation& c : corners) {
    if (pose_ids.count(c.pose_id) > 0) return;
    low = std::min(low, c.pose_id);
    high = std::max(high, c.pose_id);
  }
  throw std::invalid_argument(fmt::format(
      "{}: no pose id of the corners ({}..{}) is a pose id of the dataset ({}..{}): corners of "
      "another campaign?",
      corners_name, low, high, *pose_ids.begin(), *pose_ids.rbegin()));
}

ParameterVector WithoutCameraBlock(const ParameterVector& p, const KinematicModel& model) {
  std::unique_ptr<KinematicModel> m = model.Clone();
  p.ApplyTo(m.get());
  ParameterVector out(*m, p.X_BC(), p.X_TE());
  for (int i = 0; i < out.size(); ++i) {
    if (!p.is_free(i)) out.Fix(i, p.fixed_reason(i));
  }
  return out;
}

namespace {

// The poses the fit can use: those with at least options.min_corners_per_pose corners.
void SelectPoses(const std::vector<DatasetRow>& rows, const std::vector<PoseCorners>& corners,
                 int min_corners, std::vector<DatasetRow>* fit_rows,
                 std::vector<PoseCorners>* fit_corners, int* corner_count) {
  for (size_t j = 0; j < rows.size(); ++j) {
    if (static_cast<int>(corners[j].uv.size()) < min_corners) continue;
    fit_rows->push_back(rows[j]);
    fit_corners->push_back(corners[j]);
    *corner_count += static_cast<int>(corners[j].uv.size());
  }
}

// Levenberg-Marquardt on the free parameters from their values in `out`. Leaves r, J at the
// solution; false (with the reason in out->message) when the cost cannot be evaluated there.
bool MinimizeCorners(CornerCost* cost, const LmOptions& lm, CornerFitOutcome* out,
                     Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  const ParameterCost evaluate = [cost](const ParameterVector& p, Eigen::VectorXd* res,
                                        Eigen::MatrixXd* jac) {
    return cost->Evaluate(p, res, jac);
  };
  FreeParameterResiduals f(evaluate, out->parameters);
  Eigen::VectorXd v = out->parameters.FreeValues();
  out->minimizer = MinimizeWithLevenbergMarquardt(f, lm, &v);
  out->parameters.SetFreeValues(v);
  std::string why;
  if (!cost->Evaluate(out->parameters, r, J, &why)) {
    out->message = "the corner cost cannot be evaluated at the solution: " + why;
    return false;
  }
  return true;
}

// The fit, then the corner outliers out and a refit (once). Leaves r, J at the solution;
// false when the cost cannot be evaluated there.
bool SolveWithCornerOutliers(CornerCost* cost, const CornerFitOptions& options,
                             CornerFitOutcome* out, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  for (int round = 0; round < 2; ++round) {
    if (!MinimizeCorners(cost, options.lm, out, r, J)) return false;
    if (round == 1) break;
    const int rejected = RejectCornerOutliers(cost, *r, options.corner_outlier_chi2);
    out->rejected_corners += rejected;
    if (rejected == 0) break;
    if (!cost->Evaluate(out->parameters, r, J)) return false;
  }
  return true;
}

std::vector<PoseJointColumns> JointColumnsOf(const CornerCost& cost) {
  std::vector<PoseJointColumns> out;
  for (size_t j = 0; j < cost.corners().size(); ++j)
    out.push_back({cost.pose_offset(j), cost.joint_jacobians()[j]});
  return out;
}

// The fit again with each pose's corners weighed by their joint covariance, the encoder noise
// the first fit's residuals show (CornerCost::SetJointNoiseRatio): the generalised least
// squares estimate, whose covariance (J^T J)^-1 of the whitened cost already holds the
// encoder noise, so it replaces the first fit's sandwich. Nothing changes when no encoder
// noise was seen. False when the cost cannot be evaluated at the new solution.
bool RefitWeighingJointNoise(CornerCost* cost, const CornerFitOptions& options,
                             CornerFitOutcome* out, Eigen::VectorXd* r, Eigen::MatrixXd* J) {
  const JointNoise& noise = out->joint_noise;
  if (!noise.estimated || !(noise.sigma_q > 0)) return true;
  cost->SetJointNoiseRatio(noise.sigma_q / std::sqrt(std::max(noise.pixel_scale2, 1e-12)));
  if (!MinimizeCorners(cost, options.lm, out, r, J)) return false;
  out->uncertainty = ComputeUncertainty(out->parameters, *r, *J, /*weighted=*/true);
  cost->SetJointNoiseRatio(0);
  Eigen::VectorXd unwhitened;
  if (cost->Evaluate(out->parameters, &unwhitened, nullptr))
    out->rms_px_after = PixelRms(*cost, unwhitened);
  return true;
}

// The Wald statistic of the refined intrinsics against the file's under their covariance
// (scaled by the fit's reduced chi-square when above 1), and the number of intrinsics in it.
std::pair<double, int> FileWaldStatistic(const CornerFitOutcome& fit,
                                         const CameraIntrinsics& file) {
  const ParameterVector& p = fit.parameters;
  const Eigen::VectorXd file_values = CameraParameterValues(file);
  std::vector<Eigen::Index> rows;
  Eigen::VectorXd delta(p.camera_count());
  for (size_t f = 0; f < fit.uncertainty.free_indices.size(); ++f) {
    const int i = fit.uncertainty.free_indices[f];
    if (i < p.camera_offset()) continue;
    delta[static_cast<Eigen::Index>(rows.size())] =
        p.values()[i] - file_values[i - p.camera_offset()];
    rows.push_back(static_cast<Eigen::Index>(f));
  }
  const auto k = static_cast<Eigen::Index>(rows.size());
  if (k == 0) return {0.0, 0};
  const Eigen::MatrixXd C = fit.uncertainty.covariance(rows, rows);
  const Eigen::VectorXd d = delta.head(k);
  return {d.dot(C.ldlt().solve(d)), static_cast<int>(k)};
}

// One fit of the corner cost with the camera block free (fixed with `camera_fixed_reason`).
CornerFitOutcome FitCornersOnce(const KinematicModel& model, ModelKind kind,
                                const ParameterVector& start, const std::vector<DatasetRow>& rows,
                                const std::vector<PoseCorners>& corners,
                                const CameraIntrinsics& camera, const CornerFitOptions& options,
                                const std::string& camera_fixed_reason) {
  CornerFitOutcome out{WithCameraBlock(start, camera, camera_fixed_reason), camera};
  std::vector<DatasetRow> fit_rows;
  std::vector<PoseCorners> fit_corners;
  SelectPoses(rows, corners, options.min_corners_per_pose, &fit_rows, &fit_corners, &out.corners);
  out.poses = static_cast<int>(fit_rows.size());
  if (out.poses < 3) {
    out.message = fmt::format("{} poses have at least {} corners; the corner path needs 3",
                              out.poses, options.min_corners_per_pose);
    return out;
  }
  CornerCost cost(model, fit_rows, fit_corners, camera);
  if (camera_fixed_reason.empty() && options.use_file_covariance && camera.intrinsics_covariance) {
    out.camera_prior =
        cost.SetCameraPrior(CameraParameterValues(camera), *camera.intrinsics_covariance);
  }
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  std::string why;
  if (!cost.Evaluate(out.parameters, &r, &J, &why)) {
    out.message = "the corner cost cannot be evaluated at the start: " + why;
    return out;
  }
  out.rms_px_before = PixelRms(cost, r);
  IdentifiabilityOptions id_options = options.identifiability;
  if (id_options.preferences.empty()) id_options.preferences = DefaultFixPreferences(kind);
  for (const std::string& name : CameraFixPreferences(camera))
    id_options.preferences.push_back(name);
  out.identifiability = AnalyzeIdentifiability(J, kind, id_options, &out.parameters);
  if (!SolveWithCornerOutliers(&cost, options, &out, &r, &J)) return out;
  out.rms_px_after = PixelRms(cost, r);
  out.uncertainty = ComputeUncertainty(out.parameters, r, J, /*weighted=*/true);
  out.joint_noise = AddJointNoise(out.parameters, r, J, JointColumnsOf(cost), &out.uncertainty);
  if (options.weigh_joint_noise && !RefitWeighingJointNoise(&cost, options, &out, &r, &J)) {
    return out;
  }
  out.camera = WithCameraParameters(camera, out.parameters.camera_values());
  out.ok = out.minimizer.converged && out.uncertainty.ok;
  out.message = fmt::format(
      "{} poses, {} corners ({} rejected): corner RMS {:.4f} -> {:.4f} px, chi2/dof {:.3g}, "
      "joint noise seen {:.3g} urad{}",
      out.poses, out.corners, out.rejected_corners, out.rms_px_before, out.rms_px_after,
      out.uncertainty.chi2_per_dof, 1e6 * out.joint_noise.sigma_q,
      out.camera_prior ? "; intrinsics weighed by the camera file's covariance" : "");
  return out;
}

}  // namespace

CornerFitOutcome FitCorners(const KinematicModel& model, ModelKind kind,
                            const ParameterVector& start, const std::vector<DatasetRow>& rows,
                            const std::vector<PoseCorners>& corners, const CameraIntrinsics& camera,
                            const CornerFitOptions& options) {
  if (options.camera_fixed) {
    return FitCornersOnce(model, kind, start, rows, corners, camera, options,
                          "kept from the camera file (--camera-fixed)");
  }
  CornerFitOutcome fit = FitCornersOnce(model, kind, start, rows, corners, camera, options, "");
  const bool testable = fit.ok && !fit.camera_prior && options.file_consistency_significance > 0;
  if (!testable) return fit;
  const auto [wald, k] = FileWaldStatistic(fit, camera);
  const double p_value = k > 0 ? ChiSquareUpperTail(wald, k) : 1.0;
  fit.file_wald_statistic = wald;
  fit.file_p_value = p_value;
  if (p_value < options.file_consistency_significance) return fit;
  CornerFitOutcome kept = FitCornersOnce(
      model, kind, start, rows, corners, camera, options,
      fmt::format("kept from the camera file: the corners do not show it wrong (Wald {:.3g} on "
                  "{} intrinsics, p = {:.2g})",
                  wald, k, p_value));
  if (!kept.ok) return fit;
  kept.file_wald_statistic = wald;
  kept.file_p_value = p_value;
  kept.camera_kept = true;
  kept.message += fmt::format(
      "; the camera file agrees with the corners (Wald {:.3g} on {} intrinsics, p = {:.2g}): "
      "its intrinsics kept",
      wald, k, p_value);
  return kept;
}

std::vector<DatasetRow> RefitBoardPoses(const std::vector<DatasetRow>& rows,
                                        const std::vector<PoseCorners>& corners,
                                        const CameraIntrinsics& camera, int min_corners,
                                        std::vector<int64_t>* dropped) {
  std::vector<DatasetRow> out;
  for (size_t j = 0; j < rows.size(); ++j) {
    DatasetRow row = rows[j];
    Eigen::Matrix<double, 6, 6> C;
    if (static_cast<int>(corners[j].uv.size()) < min_corners ||
        !FitBoardPose(corners[j], camera, rows[j].X_CT, &row.X_CT, &C)) {
      if (dropped != nullptr) dropped->push_back(row.pose_id);
      continue;
    }
    row.sigma_r = std::sqrt(C.topLeftCorner<3, 3>().trace() / 3);
    row.sigma_t = std::sqrt(C.bottomRightCorner<3, 3>().trace() / 3);
    out.push_back(row);
  }
  return out;
}

}  // namespace h4::host

namespace h4::host {
namespace {

std::vector<DatasetRow> RowsWithIds(const std::vector<DatasetRow>& rows,
                                    const std::vector<int64_t>& ids) {
  std::vector<DatasetRow> out;
  for (const DatasetRow& row : rows) {
    if (std::find(ids.begin(), ids.end(), row.pose_id) != ids.end()) out.push_back(row);
  }
  return out;
}

std::vector<PoseCorners> CornersOfRows(const std::vector<DatasetRow>& all,
                                       const std::vector<PoseCorners>& corners,
                                       const std::vector<DatasetRow>& subset) {
  std::vector<PoseCorners> out;
  for (const DatasetRow& row : subset) {
    for (size_t j = 0; j < all.size(); ++j) {
      if (all[j].pose_id == row.pose_id) out.push_back(corners[j]);
    }
  }
  return out;
}

// The covariance of the free parameters had the camera block been exact: the Schur
// complement C_rr - C_rc C_cc^-1 C_cr (the Gaussian conditional on the intrinsics), in the
// free parameters' order with the camera rows zero. Empty without a free intrinsic.
std::optional<Eigen::MatrixXd> ConditionedOnCamera(const ParameterVector& p, const Uncertainty& u) {
  std::vector<Eigen::Index> robot, camera;
  for (size_t f = 0; f < u.free_indices.size(); ++f) {
    (u.free_indices[f] >= p.camera_offset() ? camera : robot)
        .push_back(static_cast<Eigen::Index>(f));
  }
  if (camera.empty()) return std::nullopt;
  const Eigen::MatrixXd C_rr = u.covariance(robot, robot);
  const Eigen::MatrixXd C_rc = u.covariance(robot, camera);
  const Eigen::MatrixXd C_cc = u.covariance(camera, camera);
  const Eigen::MatrixXd conditioned = C_rr - C_rc * C_cc.ldlt().solve(C_rc.transpose());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(u.covariance.rows(), u.covariance.cols());
  out(robot, robot) = 0.5 * (conditioned + conditioned.transpose());
  return out;
}

// The corner fit's values, sigmas and covariance in place of the pose-path refit's (the
// corner fit is the efficient estimate); the refit's verdict, cross-validation and pose
// lists stay: they judge the same campaign on the re-measured poses.
void ApplyCornerFit(const CornerFitOutcome& fit, const KinematicModel& model,
                    const std::vector<DatasetRow>& calib, double board_size_sigma,
                    IdentificationOutcome* outcome) {
  IdentificationResult& result = outcome->result;
  const ParameterVector& p = fit.parameters;
  const Uncertainty& u = fit.uncertainty;
  const Eigen::Index n = static_cast<Eigen::Index>(result.parameters.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  const std::optional<Eigen::MatrixXd> conditioned = ConditionedOnCamera(p, u);
  Eigen::MatrixXd C_camera_exact = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::Index> free_row(static_cast<size_t>(p.size()), -1);
  for (size_t f = 0; f < u.free_indices.size(); ++f) {
    free_row[static_cast<size_t>(u.free_indices[f])] = static_cast<Eigen::Index>(f);
  }
  for (Eigen::Index a = 0; a < n; ++a) {
    ResultParameter& rp = result.parameters[static_cast<size_t>(a)];
    const int i = p.IndexOf(rp.name);
    rp.value = p.values()[i];
    rp.fixed = !p.is_free(i);
    rp.std.reset();
    const Eigen::Index fa = free_row[static_cast<size_t>(i)];
    if (fa < 0) continue;
    rp.std = u.std[fa];
    for (Eigen::Index b = 0; b < n; ++b) {
      const Eigen::Index fb =
          free_row[static_cast<size_t>(p.IndexOf(result.parameters[static_cast<size_t>(b)].name))];
      if (fb < 0) continue;
      C(a, b) = 0.5 * (u.covariance(fa, fb) + u.covariance(fb, fa));
      if (conditioned) C_camera_exact(a, b) = (*conditioned)(fa, fb);
    }
  }
  result.parameter_covariance = C;
  result.parameter_covariance_camera_exact.reset();
  if (conditioned) result.parameter_covariance_camera_exact = C_camera_exact;
  result.X_BC = p.X_BC();
  result.X_TE = p.X_TE();
  outcome->parameters = WithoutCameraBlock(p, model);
  // Where the robot goes (robot_accuracy.h); the board-position figure stays the refit's.
  result.predicted_robot_accuracy_m = PredictedRobotAccuracy(model, p, calib, u, board_size_sigma);
}

}  // namespace

ResultCamera ResultCameraOf(const CornerFitOutcome& fit, const CameraIntrinsics& file_camera) {
  ResultCamera out;
  out.distortion_model = ToString(fit.camera.distortion_model);
  out.width = fit.camera.width;
  out.height = fit.camera.height;
  out.skew = fit.camera.K(0, 1);
  const ParameterVector& p = fit.parameters;
  const Eigen::VectorXd file_values = CameraParameterValues(file_camera);
  const int n = p.camera_count();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  const std::vector<int>& free = fit.uncertainty.free_indices;
  for (int a = 0; a < n; ++a) {
    const int i = p.camera_offset() + a;
    ResultCameraParameter entry;
    entry.name = p.names()[static_cast<size_t>(i)];
    entry.value = p.values()[i];
    entry.file_value = file_values[a];
    entry.fixed_reason = p.fixed_reason(i);
    const auto k = std::find(free.begin(), free.end(), i);
    if (k != free.end() && fit.uncertainty.ok) {
      const Eigen::Index ka = k - free.begin();
      entry.std = fit.uncertainty.std[ka];
      for (int b = 0; b < n; ++b) {
        const auto l = std::find(free.begin(), free.end(), p.camera_offset() + b);
        if (l != free.end()) C(a, b) = fit.uncertainty.covariance(ka, l - free.begin());
      }
    }
    out.parameters.push_back(entry);
  }
  if (fit.uncertainty.ok) out.covariance = C;
  out.corners = fit.corners;
  out.rejected_corners = fit.rejected_corners;
  out.corner_rms_px = fit.rms_px_after;
  return out;
}

CornerPathOutcome IdentifyOnCorners(const AprioriModel& apriori, ModelKind kind,
                                    const IdentificationOutcome& pose_path,
                                    const std::vector<DatasetRow>& rows,
                                    const std::vector<PoseCorners>& corners,
                                    const CameraIntrinsics& camera,
                                    const IdentificationOptions& options,
                                    const CornerFitOptions& corner_options) {
  const IdentificationResult& first = pose_path.result;
  const std::vector<DatasetRow> calib = RowsWithIds(rows, first.calib_poses);
  CornerPathOutcome out{FitCorners(*apriori.model, kind, pose_path.parameters, calib,
                                   CornersOfRows(rows, corners, calib), camera, corner_options),
                        {},
                        {},
                        pose_path};
  if (!out.fit.ok) return out;
  out.rows = RefitBoardPoses(rows, corners, out.fit.camera, corner_options.min_corners_per_pose,
                             &out.dropped);
  // Model 31 judges the poses the pose path rejected again, as --from does (identification.h).
  std::vector<int64_t> calib_ids = first.calib_poses;
  calib_ids.insert(calib_ids.end(), first.rejected_poses.begin(), first.rejected_poses.end());
  const ParameterVector start = WithoutCameraBlock(out.fit.parameters, *apriori.model);
  // The poses measured again no longer carry the file's error: the corner fit's covariance
  // holds what is left of the camera's uncertainty.
  IdentificationOptions refit_options = options;
  refit_options.camera_file.reset();
  out.outcome =
      IdentifyFromStart(*apriori.model, apriori.parameters, start, RowsWithIds(out.rows, calib_ids),
                        RowsWithIds(out.rows, first.valid_poses), refit_options);
  if (!out.outcome.summary.usable) return out;
  // The final poses are the refit's (its outlier judgement on unbiased poses): the corner
  // fit again on exactly those when they differ, from where it ended.
  const std::vector<DatasetRow> final_calib = RowsWithIds(rows, out.outcome.result.calib_poses);
  if (out.outcome.result.calib_poses != first.calib_poses) {
    CornerFitOutcome refit =
        FitCorners(*apriori.model, kind, start, final_calib,
                   CornersOfRows(rows, corners, final_calib), camera, corner_options);
    if (refit.ok) out.fit = std::move(refit);
  }
  ApplyCornerFit(out.fit, *apriori.model, RowsWithIds(out.rows, out.outcome.result.calib_poses),
                 options.board_size_sigma.value_or(0.0), &out.outcome);
  out.outcome.result.camera = ResultCameraOf(out.fit, camera);
  out.outcome.result.log.insert(
      out.outcome.result.log.begin(),
      "corner path: " + out.fit.message +
          "; values, sigmas and covariance from the corner fit, the verdict and cross-validation "
          "from the pose path on the poses measured again with the refined camera");
  return out;
}

}  // namespace h4::host
