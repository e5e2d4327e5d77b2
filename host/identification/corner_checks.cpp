// The corner path's checks at its entry; see corner_checks.h.
#include "host/identification/corner_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>


namespace h4::host {
namespace {

bool InImage(const CornerObservation& c, const CameraIntrinsics& camera) {
  const double m = kCornerImageMarginPx;
  // The image spans [-0.5, size - 0.5] px in OpenCV's convention (pixel centres at integers).
  return c.u >= -0.5 - m && c.u <= camera.width - 0.5 + m && c.v >= -0.5 - m &&
         c.v <= camera.height - 0.5 + m;
}

}  // namespace

void RequireCornersInImage(const std::vector<DatasetRow>& rows,
                           const std::vector<CornerObservation>& corners,
                           const CameraIntrinsics& camera) {
  std::set<int64_t> ids;
  for (const DatasetRow& row : rows) ids.insert(row.pose_id);
  std::map<int64_t, int> total, outside;
  std::map<int64_t, const CornerObservation*> first_outside;
  for (const CornerObservation& c : corners) {
    if (!ids.count(c.pose_id)) continue;
    ++total[c.pose_id];
    if (InImage(c, camera)) continue;
    if (outside[c.pose_id]++ == 0) first_outside[c.pose_id] = &c;
  }
  const std::string image = fmt::format("the camera's {}x{} image (+ {:g} px)", camera.width,
                                        camera.height, kCornerImageMarginPx);
  for (const auto& [pose_id, count] : outside) {
    if (count == total[pose_id]) {
      throw std::invalid_argument(fmt::format(
          "pose {}: every one of its {} corners is off {}: corners of another camera or image "
          "size? (check --camera against the camera that measured them)",
          pose_id, count, image));
    }
  }
  for (const auto& [pose_id, c] : first_outside) {
    throw std::invalid_argument(fmt::format(
        "pose {}: corner {} (tag {}) at ({:g}, {:g}) px is outside {}{}", pose_id, c->corner,
        c->tag_id, c->u, c->v, image,
        outside[pose_id] > 1 ? fmt::format(", {} such corners", outside[pose_id]) : std::string()));
  }
}

std::vector<std::string> DropDegenerateCornerPoses(const std::vector<DatasetRow>& rows,
                                                   std::vector<PoseCorners>* grouped) {
  std::vector<std::string> reasons;
  for (size_t j = 0; j < grouped->size() && j < rows.size(); ++j) {
    PoseCorners& c = (*grouped)[j];
    if (c.uv.empty()) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& uv : c.uv) mean += uv;
    mean /= static_cast<double>(c.uv.size());
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& uv : c.uv) covariance += (uv - mean) * (uv - mean).transpose();
    covariance /= static_cast<double>(c.uv.size());
    const double spread = std::sqrt(std::max(
        0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance, Eigen::EigenvaluesOnly)
                 .eigenvalues()[0]));
    if (spread >= kMinCornerSpreadPx) continue;
    reasons.push_back(fmt::format(
        "pose {}: its {} corners spread {:.3g} px across at most (on one pixel or one line, "
        "below {:g} px): no board pose follows from them, left out",
        rows[j].pose_id, c.uv.size(), spread, kMinCornerSpreadPx));
    c = PoseCorners{};
  }
  return reasons;
}

bool FlagOverstatedCornerNoise(double corner_chi2_per_dof, Verdict* code,
                               IdentificationResult* result) {
  if (!(corner_chi2_per_dof < kOverstatedCornerChi2PerDof)) return false;
  *code = Verdict::kNoiseOverstated;
  if (!result->verdict) result->verdict = ResultVerdict{};
  ResultVerdict& verdict = *result->verdict;
  verdict.code = VerdictCode(Verdict::kNoiseOverstated);
  verdict.text = fmt::format(
      "The corners' sigma is overstated: the corner fit's chi-square / dof is {:.3g}, below "
      "{:g} (a sigma_px over {:.1f} times the corners' scatter). The chi-square test cannot see "
      "a misfit under such a sigma, and the covariance is inflated: give the corners' real "
      "sigma_px (--corner-sigma for corners without one).",
      corner_chi2_per_dof, kOverstatedCornerChi2PerDof,
      1.0 / std::sqrt(kOverstatedCornerChi2PerDof));
  verdict.figures.emplace_back("corner_chi2_per_dof", corner_chi2_per_dof);
  return true;
}

}  // namespace h4::host
