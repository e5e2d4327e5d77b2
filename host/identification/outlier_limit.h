// The limit a pose's held-out score is judged against, allowing for pose covariances that are
// right on average but off pose by pose.
//
// A real camera's pose covariance comes from its corner noise; the image pipeline's biases
// (blur, response curve, lighting) move some poses by more than that, others by less. Model
// the score of a clean pose as f * X, X ~ chi-square(6) and log f ~ N(0, s^2) (the median
// excess is divided out beforehand, so f has median 1). The spread s shows in the scores'
// interquartile range on a log scale: IQR^2 ~ IQR_chi2^2 + (1.349 s)^2 (independent parts
// add their variances; 1.349 is a normal distribution's IQR in sigmas). The limit is the
// score that a clean pose exceeds with the same small probability as a chi-square(6) exceeds
// `chi2_limit`; at s = 0 it is chi2_limit itself. Gross outliers, a few percent of the poses,
// hardly move the quartiles.
#pragma once

#include <vector>

namespace h4::host {

/// P(X > x) for X ~ chi-square with 6 degrees of freedom: e^(-x/2) (1 + x/2 + x^2/8).
double ChiSquare6Survival(double x);

/// s from the scores' quartiles (above); 0 when there are fewer than 8 scores or the spread
/// is no wider than chi-square(6)'s. Quartiles are noisy: over 81 chi-square scores ln(Q3 /
/// Q1) has a standard deviation of about 0.11, so a clean campaign reads up to s = 0.4
/// (limit twice chi2_limit) one time in twenty; the identification withholds the allowance
/// from poses that are far off in millimetres (IdentificationOptions).
double ScoreSpread(std::vector<double> scores);

/// The score that f * X exceeds with probability ChiSquare6Survival(chi2_limit), for log f ~
/// N(0, spread^2). Precondition: chi2_limit > 0, spread >= 0.
double OverdispersedLimit(double chi2_limit, double spread);

}  // namespace h4::host
