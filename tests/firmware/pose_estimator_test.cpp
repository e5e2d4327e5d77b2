// Tests for firmware/pose/pose_estimator: exact recovery, the planar ambiguity, the
// Jacobian, and the covariance against Monte-Carlo error statistics.
#include "firmware/pose/pose_estimator.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "common/board/board_model.h"
#include "common/geometry/rotation.h"
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
    const RigidTransform X_CT = scenes::BoardPose(spec, 1.0, 8.0 * M_PI / 180, trial * 0.3, 0.2);
    const PoseEstimate estimate = EstimatePose(Project(board, camera, X_CT, 0.05, &rng), camera);
    ASSERT_TRUE(estimate.ok());
    EXPECT_LT(So3Log(estimate.X_CT.rotation().transpose() * X_CT.rotation()).norm(),
              4.0 * M_PI / 180)
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

TEST(PoseEstimatorTest, CovarianceMatchesMonteCarloErrors) {
  const BoardModel board(scenes::PaperBoard());
  const CameraModel camera(scenes::PaperCamera());
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.7, 0.2);
  cv::RNG rng(17);
  const int trials = 300;
  double mahalanobis = 0;
  Eigen::Matrix<double, 6, 1> sum_sq = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> predicted = Eigen::Matrix<double, 6, 1>::Zero();
  for (int t = 0; t < trials; ++t) {
    const PoseEstimate e = EstimatePose(Project(board, camera, X_CT, 0.05, &rng), camera);
    ASSERT_TRUE(e.ok());
    Eigen::Matrix<double, 6, 1> err;
    err.head<3>() = e.X_CT.translation() - X_CT.translation();
    err.tail<3>() = So3Log(X_CT.rotation().transpose() * e.X_CT.rotation());  // right, in T
    mahalanobis += err.dot(e.covariance.ldlt().solve(err)) / trials;
    sum_sq += err.cwiseAbs2() / trials;
    predicted += e.covariance.diagonal() / trials;
  }
  // E[e^T S^-1 e] = 6 for a correct covariance; 300 trials: standard error ~0.2.
  EXPECT_NEAR(mahalanobis, 6.0, 0.8);
  for (int k = 0; k < 6; ++k) {
    const double ratio = std::sqrt(sum_sq[k] / predicted[k]);
    EXPECT_GT(ratio, 0.8) << k;
    EXPECT_LT(ratio, 1.25) << k;
  }
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
