// Draws a robot away from its nominal geometry: each value moves by a scale times a unit draw of
// the distribution, and a placement by its translation and roll-pitch-yaw the same way. The
// simulated true robot draws normal deviations (scale: a standard deviation); the robust
// planning study draws uniform ones (scale: a half width).
#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"

namespace h4::host {

/// `UnitDistribution`: a std:: real distribution of unit spread (e.g. normal(0, 1)).
template <typename UnitDistribution>
class DeviationDraw {
 public:
  DeviationDraw(uint64_t seed, UnitDistribution unit) : rng_(seed), unit_(unit) {}

  /// value + scale * one unit draw.
  double operator()(double value, double scale) { return value + scale * unit_(rng_); }

  /// X with each translation component moved by `translation` and each of roll, pitch, yaw
  /// by `rotation` (x, y, z, then roll, pitch, yaw: the order the draws are taken in).
  RigidTransform Placement(const RigidTransform& X, double translation, double rotation) {
    Eigen::Vector3d t = X.translation(), rpy = X.rpy();
    for (int k = 0; k < 3; ++k) t[k] = (*this)(t[k], translation);
    for (int k = 0; k < 3; ++k) rpy[k] = (*this)(rpy[k], rotation);
    return RigidTransform::FromTranslationRpy(t, rpy);
  }

 private:
  std::mt19937_64 rng_;
  UnitDistribution unit_;
};

/// Normal deviations: the scale is a standard deviation.
class NormalDeviationDraw : public DeviationDraw<std::normal_distribution<double>> {
 public:
  explicit NormalDeviationDraw(uint64_t seed)
      : DeviationDraw(seed, std::normal_distribution<double>(0.0, 1.0)) {}
};

/// Uniform deviations: the scale is a half width.
class UniformDeviationDraw : public DeviationDraw<std::uniform_real_distribution<double>> {
 public:
  explicit UniformDeviationDraw(uint64_t seed)
      : DeviationDraw(seed, std::uniform_real_distribution<double>(-1.0, 1.0)) {}
};

}  // namespace h4::host
