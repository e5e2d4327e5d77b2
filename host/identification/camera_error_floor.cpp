// The camera's error floor of a solution; see camera_error_floor.h.
#include "host/identification/camera_error_floor.h"

#include <algorithm>
#include <cmath>

namespace h4::host {
namespace {

// sum_j error2[j] / (sigma[j]^2 + f^2) / 3 n: decreasing in f.
double NormalisedChi2(const std::vector<double>& error2, const std::vector<double>& sigma,
                      double f) {
  double sum = 0.0;
  for (size_t j = 0; j < error2.size(); ++j) sum += error2[j] / (sigma[j] * sigma[j] + f * f);
  return sum / (3.0 * static_cast<double>(error2.size()));
}

}  // namespace

double ErrorFloorOf(const std::vector<double>& error2, const std::vector<double>& sigma,
                    double dof_share) {
  if (error2.empty() || error2.size() != sigma.size() || !(dof_share > 0.0)) return 0.0;
  if (NormalisedChi2(error2, sigma, 0.0) <= dof_share) return 0.0;
  // At f^2 = the largest error2 / dof_share the normalised sum is at most dof_share / 3.
  double low = 0.0;
  double high = std::sqrt(*std::max_element(error2.begin(), error2.end()) / dof_share);
  for (int k = 0; k < 100 && high - low > 1e-12 * high; ++k) {
    const double mid = 0.5 * (low + high);
    (NormalisedChi2(error2, sigma, mid) > dof_share ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

std::optional<CameraErrorFloor> CameraErrorFloorAt(const KinematicModel& model,
                                                   const ParameterVector& p,
                                                   const std::vector<DatasetRow>& in_fit,
                                                   const CostOptions& cost) {
  IdentificationCost measurement(CostKind::kMeasurement, model, in_fit, cost);
  Eigen::VectorXd r;
  if (in_fit.empty() || !measurement.Evaluate(p, &r, nullptr)) return std::nullopt;
  const double residuals = static_cast<double>(r.size());
  const double dof_share = 1.0 - static_cast<double>(p.free_count()) / residuals;
  if (!(dof_share > 0.0)) return std::nullopt;
  std::vector<double> rotation_error2, rotation_sigma, translation_error2, translation_sigma;
  for (size_t j = 0; j < in_fit.size(); ++j) {
    const auto row = static_cast<Eigen::Index>(6 * j);
    rotation_sigma.push_back(1.0 / measurement.RotationWeight(in_fit[j]));
    translation_sigma.push_back(1.0 / measurement.TranslationWeight(in_fit[j]));
    // r is in units of the stated sigmas (identification_cost.h): back to rad and m.
    rotation_error2.push_back(r.segment<3>(row).squaredNorm() * std::pow(rotation_sigma.back(), 2));
    translation_error2.push_back(r.segment<3>(row + 3).squaredNorm() *
                                 std::pow(translation_sigma.back(), 2));
  }
  return CameraErrorFloor{ErrorFloorOf(rotation_error2, rotation_sigma, dof_share),
                          ErrorFloorOf(translation_error2, translation_sigma, dof_share)};
}

}  // namespace h4::host
