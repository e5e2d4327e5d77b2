// The outlier limit under pose-to-pose spread of the covariances; see outlier_limit.h.
#include "host/identification/outlier_limit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace h4::host {
namespace {

// Quartiles of chi-square(6): ln(Q3 / Q1) = ln(7.8408 / 3.4546), its IQR on a log scale.
constexpr double kChi2SixLogIqr = 0.81960;
// A normal distribution's interquartile range, in standard deviations.
constexpr double kNormalIqr = 1.34898;


// The q-quantile of sorted values, by linear interpolation.
double Quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(at));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (at - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

// P(f X > limit) for log f ~ N(0, s^2): the survival averaged over f (Simpson's rule on
// +-8 standard deviations of log f, where the normal density is below 1e-14).
double MixtureSurvival(double limit, double s) {
  constexpr int kIntervals = 400;  // even
  constexpr double kReach = 8.0;
  const double h = 2.0 * kReach / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double u = -kReach + i * h;
    const double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    const double density = std::exp(-0.5 * u * u) / std::sqrt(2.0 * std::numbers::pi);
    sum += weight * density * ChiSquare6Survival(limit * std::exp(-s * u));
  }
  return sum * h / 3.0;
}

}  // namespace

double ChiSquare6Survival(double x) {
  if (x <= 0.0) return 1.0;
  return std::exp(-0.5 * x) * (1.0 + 0.5 * x + 0.125 * x * x);
}

double ScoreSpread(std::vector<double> scores) {
  std::erase_if(scores, [](double score) { return !(score > 0.0); });
  if (scores.size() < 8) return 0.0;
  std::sort(scores.begin(), scores.end());
  const double log_iqr = std::log(Quantile(scores, 0.75) / Quantile(scores, 0.25));
  const double excess = log_iqr * log_iqr - kChi2SixLogIqr * kChi2SixLogIqr;
  return excess > 0.0 ? std::sqrt(excess) / kNormalIqr : 0.0;
}

double OverdispersedLimit(double chi2_limit, double spread) {
  if (!(spread > 0.0)) return chi2_limit;
  const double tail = ChiSquare6Survival(chi2_limit);
  // MixtureSurvival falls as the limit grows: bisect on log(limit), from chi2_limit (the
  // mixture's tail is heavier, so it is exceeded more often) up to a limit far past it.
  double low = std::log(chi2_limit);
  double high = low + 12.0 * spread + 1.0;
  while (MixtureSurvival(std::exp(high), spread) > tail) high += 12.0 * spread + 1.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (low + high);
    (MixtureSurvival(std::exp(mid), spread) > tail ? low : high) = mid;
  }
  return std::exp(0.5 * (low + high));
}

}  // namespace h4::host
