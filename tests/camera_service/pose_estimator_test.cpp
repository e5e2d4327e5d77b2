// Tests for firmware/pose/pose_estimator: exact recovery, the planar ambiguity, the
// Jacobian, and the covariance against Monte-Carlo error statistics.
#include "firmware/pose/pose_estimator.h"

#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "common/board/board_model.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

std::vector<CornerObservation> Project(const BoardModel& board, const CameraModel& camera,
                                       const RigidTransform& X_CT, double noise_px, cv::RNG* rng) {
  std::vector<CornerObservation> corners;
  for (int id = 0; id < board.corner_count(); ++id) {
    CornerObservation c;
    c.id = id;
    c.p_TQ = board.corners()[static_cast<size_t>(id)];
    camera.Project(X_CT * c.p_TQ, &c.uv);
    if (noise_px > 0) c.uv += Eigen::Vector2d(rng->gaussian(noise_px), rng->gaussian(noise_px));
    corners.push_back(c);
  }
  return corners;
}

// Erosion directions of tag corners as the edge fit derives them: corner k of a tag (4
// consecutive ids) moves by -m when its quad's sides move inward by 1 px, with
// [n1^T; n2^T] m = [1; 1] for the outward normals of its two sides.
void SetTagErosionDirections(std::vector<CornerObservation>* corners) {
  for (size_t first = 0; first + 3 < corners->size(); first += 4) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (size_t k = 0; k < 4; ++k) centre += 0.25 * (*corners)[first + k].uv;
    auto outward_normal = [&](size_t a, size_t b) {
      const Eigen::Vector2d d = (*corners)[first + b].uv - (*corners)[first + a].uv;
      Eigen::Vector2d n(-d.y(), d.x());
      n.normalize();
      const Eigen::Vector2d mid = 0.5 * ((*corners)[first + a].uv + (*corners)[first + b].uv);
      return n.dot(mid - centre) < 0 ? Eigen::Vector2d(-n) : n;
    };
    for (size_t k = 0; k < 4; ++k) {
      Eigen::Matrix2d A;
      A.row(0) = outward_normal((k + 3) % 4, k).transpose();
      A.row(1) = outward_normal(k, (k + 1) % 4).transpose();
      (*corners)[first + k].erosion_px = -(A.inverse() * Eigen::Vector2d(1, 1));
      (*corners)[first + k].edge_group = static_cast<int>(first / 4);
    }
  }
}

TEST(PoseEstimatorTest, ExactCornersGiveTheExactPose) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  for (const RigidTransform& X_CT : scenes::RandomPoses(5, 3)) {
    const PoseEstimate estimate = EstimatePose(Project(board, camera, X_CT, 0, nullptr), camera);
    ASSERT_TRUE(estimate.ok()) << estimate.message;
    EXPECT_TRUE(estimate.X_CT.IsNearlyEqualTo(X_CT, 1e-9, 1e-9));
    EXPECT_LT(estimate.rms_px, 1e-8);
    EXPECT_EQ(estimate.corners, 144);
  }
}

// The per-corner sigma that travels with the pose (common/formats/README.md#board-corners-csv) is
// the noise the covariance takes for that corner: the residuals' sigma with kResidual, the corner's
// own edge-fit noise (plus the excess) with kEdgeNoise; the floor on top of both.
TEST(PoseEstimatorTest, CornerSigmasAreTheNoiseTheCovarianceTakes) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::RandomPoses(1, 3)[0];
  cv::RNG rng(11);
  PoseOptions residual;
  residual.covariance = CovarianceModel::kResidual;
  residual.corner_floor_px = 0;
  const PoseEstimate noisy =
      EstimatePose(Project(board, camera, X_CT, 0.1, &rng), camera, residual);
  ASSERT_TRUE(noisy.ok()) << noisy.message;
  ASSERT_EQ(noisy.corner_sigma_px.size(), 144u);
  for (const double sigma : noisy.corner_sigma_px) EXPECT_NEAR(sigma, 0.1, 0.015);

  std::vector<CornerObservation> exact = Project(board, camera, X_CT, 0, nullptr);
  for (CornerObservation& c : exact) {
    c.noise_px(0, 0) = 0.03;
    c.noise_px(1, 1) = c.id == 5 ? 0.08 : 0.04;
  }
  PoseOptions edge_noise;  // kEdgeNoise, floor 0.0015 px (no erosion fitted: no directions)
  const PoseEstimate estimate = EstimatePose(exact, camera, edge_noise);
  ASSERT_TRUE(estimate.ok()) << estimate.message;
  ASSERT_EQ(estimate.corner_sigma_px.size(), exact.size());
  const double floor2 = edge_noise.corner_floor_px * edge_noise.corner_floor_px;
  EXPECT_NEAR(estimate.corner_sigma_px[0], std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2 + floor2),
              1e-12);
  EXPECT_NEAR(estimate.corner_sigma_px[5], std::sqrt((0.03 * 0.03 + 0.08 * 0.08) / 2 + floor2),
              1e-12);
}

TEST(PoseEstimatorTest, NearFrontalBoardPicksTheTrueOfTheTwoPlanarSolutions) {
  // A small board (2 x 2 tags, 69 mm) at 1 m tilted by 8 degrees: the two IPPE solutions
  // are mirror tilts ~16 degrees apart, and both are local minima of the reprojection
  // error (measured: in about half the trials LM keeps them apart).
  AprilGridSpec spec = scenes::PaperBoard();
  spec.cols = 2;
  spec.rows = 2;
  const BoardModel board(spec);
  const CameraModel camera(scenes::PaperCamera());
  cv::RNG rng(5);
  int ambiguous = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const RigidTransform X_CT =
        scenes::BoardPose(spec, 1.0, RadiansFromDegrees(8.0), trial * 0.3, 0.2);
    const PoseEstimate estimate = EstimatePose(Project(board, camera, X_CT, 0.05, &rng), camera);
    ASSERT_TRUE(estimate.ok());
    EXPECT_LT(So3Log(estimate.X_CT.rotation().transpose() * X_CT.rotation()).norm(),
              RadiansFromDegrees(4.0))
        << trial;
    EXPECT_LE(estimate.rms_px, estimate.alternative_rms_px);
    if (std::isfinite(estimate.alternative_rms_px) &&
        estimate.alternative_rms_px > 1.5 * estimate.rms_px) {
      ++ambiguous;  // the mirror solution existed and was rejected
    }
  }
  EXPECT_GT(ambiguous, 0);
}

TEST(PoseEstimatorTest, ResidualJacobianMatchesFiniteDifferences) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::RandomPoses(1, 8)[0];
  const auto corners = Project(board, camera, X_CT, 0, nullptr);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  ASSERT_TRUE(ReprojectionResiduals(corners, camera, X_CT, &r, &J));
  for (int k = 0; k < 6; ++k) {
    const double h = 1e-7;
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d[k] = h;
    auto perturbed = [&](double sign) {
      const RigidTransform X(X_CT.rotation() * So3Exp(sign * d.tail<3>()),
                             X_CT.translation() + sign * d.head<3>());
      Eigen::VectorXd out;
      ReprojectionResiduals(corners, camera, X, &out);
      return out;
    };
    const Eigen::VectorXd numeric = (perturbed(1) - perturbed(-1)) / (2 * h);
    EXPECT_LT((J.col(k) - numeric).norm(), 1e-4 * numeric.norm()) << k;
  }
}

using Vector6 = Eigen::Matrix<double, 6, 1>;

// An estimate's error in the covariance's coordinates: translation, then the rotation
// error on the right (in T).
Vector6 ErrorInCovarianceOrder(const RigidTransform& estimate, const RigidTransform& truth) {
  Vector6 err;
  err.head<3>() = estimate.translation() - truth.translation();
  err.tail<3>() = So3Log(truth.rotation().transpose() * estimate.rotation());
  return err;
}

// Over Monte-Carlo trials: the mean squared error per coordinate and the mean variance two
// covariance models state for it.
struct CovarianceCheck {
  Vector6 mean_sq_error = Vector6::Zero();
  Vector6 stated = Vector6::Zero();
  Vector6 stated_other = Vector6::Zero();
  /// Actual over stated sigma, per coordinate, for the tested and the other model.
  Vector6 Ratio() const { return mean_sq_error.cwiseQuotient(stated).cwiseSqrt(); }
  Vector6 OtherRatio() const { return mean_sq_error.cwiseQuotient(stated_other).cwiseSqrt(); }
};

/// Each axis's actual-to-stated sigma ratio lies in (low, high).
void ExpectRatiosWithin(const Vector6& ratio, double low, double high) {
  for (int k = 0; k < 6; ++k) {
    EXPECT_GT(ratio[k], low) << k;
    EXPECT_LT(ratio[k], high) << k;
  }
}

// Estimates X_CT from `trials` noisy corner sets (`noisy_corners`) with the `tested` and
// the `other` options, and sums what CovarianceCheck holds.
CovarianceCheck CheckCovariance(
    const CameraModel& camera, const RigidTransform& X_CT,
    const std::function<std::vector<CornerObservation>(cv::RNG&)>& noisy_corners,
    const PoseOptions& tested, const PoseOptions& other, uint64_t seed, int trials) {
  cv::RNG rng(seed);
  CovarianceCheck check;
  for (int t = 0; t < trials; ++t) {
    const std::vector<CornerObservation> corners = noisy_corners(rng);
    const PoseEstimate e = EstimatePose(corners, camera, tested);
    const PoseEstimate plain = EstimatePose(corners, camera, other);
    EXPECT_TRUE(e.ok() && plain.ok());
    if (!e.ok() || !plain.ok()) return check;
    check.mean_sq_error += ErrorInCovarianceOrder(e.X_CT, X_CT).cwiseAbs2() / trials;
    check.stated += e.covariance.diagonal() / trials;
    check.stated_other += plain.covariance.diagonal() / trials;
  }
  return check;
}

TEST(PoseEstimatorTest, CovarianceMatchesMonteCarloErrors) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.7, 0.2);
  cv::RNG rng(17);
  const int trials = 300;
  double mahalanobis = 0;
  Vector6 sum_sq = Vector6::Zero();
  Vector6 predicted = Vector6::Zero();
  for (int t = 0; t < trials; ++t) {
    const PoseEstimate e = EstimatePose(Project(board, camera, X_CT, 0.05, &rng), camera);
    ASSERT_TRUE(e.ok());
    const Vector6 err = ErrorInCovarianceOrder(e.X_CT, X_CT);
    mahalanobis += err.dot(e.covariance.ldlt().solve(err)) / trials;
    sum_sq += err.cwiseAbs2() / trials;
    predicted += e.covariance.diagonal() / trials;
  }
  // E[e^T S^-1 e] = 6 for a correct covariance; 300 trials: standard error ~0.2.
  EXPECT_NEAR(mahalanobis, 6.0, 0.8);
  ExpectRatiosWithin(sum_sq.cwiseQuotient(predicted).cwiseSqrt(), 0.8, 1.25);
}

TEST(PoseEstimatorTest, UniformErosionIsFittedAndLeavesThePoseExact) {
  // Every tag eroded by 0.3 px (what gamma 0.45 with 1 px blur does): a plain fit sees a
  // smaller board, hence a farther one; the erosion parameter takes it out exactly.
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const double erosion_px = 0.3;
  for (const RigidTransform& X_CT : scenes::RandomPoses(3, 11)) {
    auto corners = Project(board, camera, X_CT, 0, nullptr);
    SetTagErosionDirections(&corners);
    for (CornerObservation& c : corners) c.uv += erosion_px * c.erosion_px;
    PoseOptions plain;
    plain.erosion = ErosionModel::kNone;
    const PoseEstimate biased = EstimatePose(corners, camera, plain);
    ASSERT_TRUE(biased.ok());
    EXPECT_GT((biased.X_CT.translation() - X_CT.translation()).norm(), 0.2e-3);  // ~0.4 mm
    for (ErosionModel model :
         {ErosionModel::kGlobal, ErosionModel::kAffine, ErosionModel::kPerTag}) {
      PoseOptions options;
      options.erosion = model;
      const PoseEstimate estimate = EstimatePose(corners, camera, options);
      ASSERT_TRUE(estimate.ok()) << estimate.message;
      EXPECT_TRUE(estimate.X_CT.IsNearlyEqualTo(X_CT, 1e-9, 1e-9));
      EXPECT_NEAR(estimate.erosion_px, erosion_px, 1e-7);
      EXPECT_EQ(estimate.erosion_parameters, model == ErosionModel::kGlobal   ? 1
                                             : model == ErosionModel::kAffine ? 3
                                                                              : 36);
    }
  }
}

TEST(PoseEstimatorTest, ErosionWidensTheDepthSigmaOnlyAsMuchAsItCorrelates) {
  // The marginal covariance with the erosion fitted is at least the plain one (the erosion
  // trades with depth), and no parameter is fitted for corners without directions.
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.7, 0.2);
  cv::RNG rng(3);
  auto corners = Project(board, camera, X_CT, 0.05, &rng);
  PoseOptions options;
  options.erosion = ErosionModel::kGlobal;
  options.covariance = CovarianceModel::kResidual;
  const PoseEstimate without_directions = EstimatePose(corners, camera, options);
  ASSERT_TRUE(without_directions.ok());
  EXPECT_EQ(without_directions.erosion_parameters, 0);
  SetTagErosionDirections(&corners);
  const PoseEstimate with_erosion = EstimatePose(corners, camera, options);
  ASSERT_TRUE(with_erosion.ok());
  EXPECT_EQ(with_erosion.erosion_parameters, 1);
  EXPECT_GE(with_erosion.covariance(2, 2), 0.99 * without_directions.covariance(2, 2));
  EXPECT_GT(with_erosion.erosion_sigma_px, 0);
  EXPECT_LT(std::abs(with_erosion.erosion_px), 5 * with_erosion.erosion_sigma_px);
}

TEST(PoseEstimatorTest, CovarianceCountsTheErrorATagSharesOnce) {
  // Each tag's four corners share an error (their sides are fitted together), plus a
  // smaller independent one: the edge-group covariance must match the Monte-Carlo spread,
  // where sigma^2 (J^T J)^-1 over independent corners understates it (measured ~2x).
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.7, 0.2);
  PoseOptions edge_group, residual;
  edge_group.covariance = CovarianceModel::kEdgeGroup;
  residual.covariance = CovarianceModel::kResidual;
  auto noisy_corners = [&](cv::RNG& rng) {
    auto corners = Project(board, camera, X_CT, 0.02, &rng);
    for (size_t first = 0; first < corners.size(); first += 4) {
      const Eigen::Vector2d shared(rng.gaussian(0.04), rng.gaussian(0.04));
      for (size_t k = first; k < first + 4; ++k) {
        corners[k].uv += shared;
        corners[k].edge_group = static_cast<int>(first / 4);
      }
    }
    return corners;
  };
  const CovarianceCheck check =
      CheckCovariance(camera, X_CT, noisy_corners, edge_group, residual, 29, 200);
  ExpectRatiosWithin(check.Ratio(), 0.75, 1.33);
  EXPECT_GT(check.OtherRatio()[2], 1.5);  // depth, the worst understated
}

// The noise of a tag's four fitted sides as the edge fit reports it (CornerNoisePx): side j
// (from corner j to j+1) has angle noise sigma_phi (rad, about its midpoint) and offset noise
// sigma_c (px); corner k, where sides k-1 and k meet, moves by A^-1 [delta_{k-1}; delta_k]
// with A = [n_{k-1}^T; n_k^T] and delta_j = dc_j + n_perp_j . (mid_j - p) dphi_j.
void SetTagSideNoise(double sigma_phi, double sigma_c, std::vector<CornerObservation>* corners) {
  for (size_t first = 0; first + 3 < corners->size(); first += 4) {
    auto at = [&](size_t k) { return (*corners)[first + k % 4].uv; };
    auto normal = [&](size_t j) {
      const Eigen::Vector2d d = at(j + 1) - at(j);
      return Eigen::Vector2d(-d.y(), d.x()).normalized();
    };
    for (size_t k = 0; k < 4; ++k) {
      const size_t sides[2] = {(k + 3) % 4, k};
      Eigen::Matrix2d A;
      A.row(0) = normal(sides[0]).transpose();
      A.row(1) = normal(sides[1]).transpose();
      const Eigen::Matrix2d A_inverse = A.inverse();
      CornerObservation& corner = (*corners)[first + k];
      corner.noise_px.setZero();
      for (int row = 0; row < 2; ++row) {
        const size_t j = sides[row];
        const Eigen::Vector2d n = normal(j), n_perp(-n.y(), n.x());
        const Eigen::Vector2d mid = 0.5 * (at(j) + at(j + 1));
        const auto column = static_cast<Eigen::Index>(2 * j);
        corner.noise_px.col(column) = A_inverse.col(row) * n_perp.dot(mid - corner.uv) * sigma_phi;
        corner.noise_px.col(column + 1) = A_inverse.col(row) * sigma_c;
      }
      corner.edge_group = static_cast<int>(first / 4);
    }
  }
}

TEST(PoseEstimatorTest, CovarianceFollowsTheNoiseATagsSidesShare) {
  // Corners moved by their sides' angle and offset noise: a side turning about its middle
  // moves its two corners in opposite directions, which the tag's centre hardly feels.
  // kEdgeNoise must match the Monte-Carlo spread; kResidual, taking the corners as
  // independent, overstates it.
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.7, 0.2);
  auto exact = Project(board, camera, X_CT, 0, nullptr);
  SetTagSideNoise(0.002, 0.005, &exact);
  PoseOptions options, residual;
  options.erosion = residual.erosion = ErosionModel::kNone;
  options.corner_floor_px = residual.corner_floor_px = 0;
  options.covariance = CovarianceModel::kEdgeNoise;
  residual.covariance = CovarianceModel::kResidual;
  auto noisy_corners = [&](cv::RNG& rng) {
    auto corners = exact;
    for (size_t first = 0; first < corners.size(); first += 4) {
      Eigen::Matrix<double, 8, 1> z;
      for (int i = 0; i < 8; ++i) z[i] = rng.gaussian(1.0);
      for (size_t k = first; k < first + 4; ++k) corners[k].uv += corners[k].noise_px * z;
    }
    return corners;
  };
  const CovarianceCheck check =
      CheckCovariance(camera, X_CT, noisy_corners, options, residual, 41, 200);
  ExpectRatiosWithin(check.Ratio(), 0.8, 1.25);
  EXPECT_LT(check.OtherRatio()[2], 0.7);  // depth: independent overstates
}

TEST(PoseEstimatorTest, TooFewCornersIsReportedNotGuessed) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  auto corners = Project(board, camera, scenes::RandomPoses(1, 2)[0], 0, nullptr);
  corners.resize(3);
  const PoseEstimate estimate = EstimatePose(corners, camera);
  EXPECT_EQ(estimate.status, PoseEstimate::Status::kTooFewCorners);
  EXPECT_FALSE(estimate.message.empty());
  EXPECT_TRUE(estimate.X_CT.translation().allFinite());
}

}  // namespace
}  // namespace h4::cam
