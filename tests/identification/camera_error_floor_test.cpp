// The camera's error floor (camera_error_floor.h): the per-axis error that, added in
// quadrature to each pose's stated sigma, makes the residuals' chi-square match their share of
// the degrees of freedom.
#include "host/identification/camera_error_floor.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace h4::host {
namespace {

// n poses with stated sigmas alternating between 1 and 2 and an actual per-axis error of
// sqrt(stated^2 + floor^2): the squared error over 3 axes of each.
struct Poses {
  std::vector<double> error2, sigma;
};

Poses Draw(int n, double floor, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Poses poses;
  for (int j = 0; j < n; ++j) {
    const double stated = j % 2 == 0 ? 1.0 : 2.0;
    const double actual = std::sqrt(stated * stated + floor * floor);
    double e2 = 0.0;
    for (int k = 0; k < 3; ++k) e2 += std::pow(actual * normal(rng), 2);
    poses.error2.push_back(e2);
    poses.sigma.push_back(stated);
  }
  return poses;
}

TEST(CameraErrorFloor, RecoversTheFloorBeyondStatedSigmasThatDiffer) {
  const Poses poses = Draw(20000, 3.0, 1);
  EXPECT_NEAR(ErrorFloorOf(poses.error2, poses.sigma, 1.0), 3.0, 0.1);
}

// A fit of n parameters absorbs a share n / m of the residuals: at a share of 1/2 the same
// residuals ask for a larger floor, here exactly one with (sigma^2 + f^2) = 2 (sigma = 1).
TEST(CameraErrorFloor, CountsTheFreeParametersOut) {
  const std::vector<double> error2(10, 3.0), sigma(10, 1.0);  // chi-square / 3n = 1
  EXPECT_EQ(ErrorFloorOf(error2, sigma, 1.0), 0.0);
  EXPECT_NEAR(ErrorFloorOf(error2, sigma, 0.5), 1.0, 1e-9);
}

TEST(CameraErrorFloor, ZeroWhenTheStatedSigmasExplainTheResidualsOrNothingIsGiven) {
  const Poses poses = Draw(2000, 0.0, 2);
  std::vector<double> error2 = poses.error2;
  for (double& e2 : error2) e2 *= 0.5;
  EXPECT_EQ(ErrorFloorOf(error2, poses.sigma, 1.0), 0.0);
  EXPECT_EQ(ErrorFloorOf({}, {}, 1.0), 0.0);
  EXPECT_EQ(ErrorFloorOf({1.0}, {1.0, 2.0}, 1.0), 0.0);
  EXPECT_EQ(ErrorFloorOf({100.0}, {1.0}, 0.0), 0.0);
}

}  // namespace
}  // namespace h4::host
