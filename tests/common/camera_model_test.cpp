// Tests for common/camera/camera_model: OpenCV's radial-tangential and equidistant
// (fisheye) models by known values, their Jacobians against finite differences, and
// undistortion inverting them over the whole image, failing where it must. (Agreement
// with cv::projectPoints and cv::fisheye itself is checked in
// tests/detection/camera_projection_test.cpp, which links OpenCV.)
#include "common/camera/camera_model.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/units.h"

namespace h4 {
namespace {

CameraIntrinsics Camera(int distortion_count) {
  CameraIntrinsics c = CameraIntrinsics::Pinhole(1024, 768, 800.0, 810.0, 512.0, 384.0);
  c.distortion = Eigen::VectorXd::Zero(distortion_count);
  const double all[8] = {-0.2, 0.05, 0.001, -0.002, 0.01, 0.02, -0.01, 0.005};
  for (int i = 0; i < distortion_count; ++i) c.distortion[i] = all[i];
  return c;
}

// A wide-angle fisheye module: 1024 x 768 at 300 px focal length sees about 90 degrees
// off-axis along the long side; the image corners are beyond 90 degrees.
CameraIntrinsics Fisheye() {
  CameraIntrinsics c = CameraIntrinsics::Pinhole(1024, 768, 300.0, 301.0, 510.0, 386.0);
  c.distortion_model = DistortionModel::kEquidistant;
  c.distortion = Eigen::Vector4d(-0.02, 0.004, -0.0015, 0.0002);
  return c;
}

// Central finite differences of Project against its analytic Jacobian.
void ExpectProjectionJacobianMatches(const CameraModel& camera, const Eigen::Vector3d& p) {
  Eigen::Vector2d uv;
  Eigen::Matrix<double, 2, 3> J;
  ASSERT_TRUE(camera.Project(p, &uv, &J));
  for (int k = 0; k < 3; ++k) {
    const double h = 1e-7 * std::max(1.0, p.norm());
    Eigen::Vector2d up, um;
    ASSERT_TRUE(camera.Project(p + h * Eigen::Vector3d::Unit(k), &up));
    ASSERT_TRUE(camera.Project(p - h * Eigen::Vector3d::Unit(k), &um));
    const Eigen::Vector2d numeric = (up - um) / (2 * h);
    EXPECT_NEAR((J.col(k) - numeric).norm(), 0.0, 1e-5 * (1 + numeric.norm()))
        << "p " << p.transpose() << " column " << k << "\nanalytic " << J.col(k).transpose()
        << "\nnumeric " << numeric.transpose();
  }
}

TEST(CameraModelTest, PinholeWithoutDistortionProjectsByHand) {
  const CameraModel camera(Camera(0));
  Eigen::Vector2d uv;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0.1, -0.05, 0.5), &uv));
  EXPECT_NEAR(uv.x(), 512.0 + 800.0 * 0.2, 1e-12);
  EXPECT_NEAR(uv.y(), 384.0 - 810.0 * 0.1, 1e-12);
}

TEST(CameraModelTest, RadialAndTangentialTermsMatchOpenCvFormula) {
  const CameraModel camera(Camera(5));
  const double x = 0.3, y = -0.2, r2 = x * x + y * y;
  const double g = 1 - 0.2 * r2 + 0.05 * r2 * r2 + 0.01 * r2 * r2 * r2;
  const double xd = x * g + 2 * 0.001 * x * y + (-0.002) * (r2 + 2 * x * x);
  const double yd = y * g + 0.001 * (r2 + 2 * y * y) + 2 * (-0.002) * x * y;
  const Eigen::Vector2d uv = camera.PixelFromNormalized(Eigen::Vector2d(x, y));
  EXPECT_NEAR(uv.x(), 800.0 * xd + 512.0, 1e-10);
  EXPECT_NEAR(uv.y(), 810.0 * yd + 384.0, 1e-10);
}

TEST(CameraModelTest, RationalModelDividesByDenominator) {
  const CameraModel camera(Camera(8));
  const double x = 0.25, y = 0.1, r2 = x * x + y * y;
  const double g = (1 - 0.2 * r2 + 0.05 * r2 * r2 + 0.01 * r2 * r2 * r2) /
                   (1 + 0.02 * r2 - 0.01 * r2 * r2 + 0.005 * r2 * r2 * r2);
  const Eigen::Vector2d xd = camera.Distort(Eigen::Vector2d(x, y));
  EXPECT_NEAR(xd.x(), x * g + 2 * 0.001 * x * y - 0.002 * (r2 + 2 * x * x), 1e-14);
  EXPECT_NEAR(xd.y(), y * g + 0.001 * (r2 + 2 * y * y) - 2 * 0.002 * x * y, 1e-14);
}

TEST(CameraModelTest, ProjectionJacobianMatchesFiniteDifferences) {
  for (int n : {4, 5, 8}) {
    const CameraModel camera(Camera(n));
    const Eigen::Vector3d p(0.12, -0.08, 0.55);
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J;
    ASSERT_TRUE(camera.Project(p, &uv, &J));
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-7;
      Eigen::Vector2d up, um;
      camera.Project(p + h * Eigen::Vector3d::Unit(k), &up);
      camera.Project(p - h * Eigen::Vector3d::Unit(k), &um);
      const Eigen::Vector2d numeric = (up - um) / (2 * h);
      EXPECT_NEAR((J.col(k) - numeric).norm(), 0.0, 1e-5 * (1 + numeric.norm())) << n << " " << k;
    }
  }
}

TEST(CameraModelTest, EquidistantModelMatchesTheFisheyeFormula) {
  const CameraModel camera(Fisheye());
  const double x = 0.9, y = -0.6, r = std::hypot(x, y), theta = std::atan(r);
  const double t2 = theta * theta;
  const double theta_d = theta * (1 - 0.02 * t2 + 0.004 * t2 * t2 - 0.0015 * t2 * t2 * t2 +
                                  0.0002 * t2 * t2 * t2 * t2);
  const Eigen::Vector2d uv = camera.PixelFromNormalized(Eigen::Vector2d(x, y));
  EXPECT_NEAR(uv.x(), 300.0 * theta_d / r * x + 510.0, 1e-10);
  EXPECT_NEAR(uv.y(), 301.0 * theta_d / r * y + 386.0, 1e-10);
  // On the axis the image is the principal point; the plain f-theta lens has no coefficients.
  EXPECT_EQ(camera.PixelFromNormalized(Eigen::Vector2d::Zero()), Eigen::Vector2d(510.0, 386.0));
  CameraIntrinsics f_theta = Fisheye();
  f_theta.distortion.resize(0);
  const Eigen::Vector2d xd = CameraModel(f_theta).Distort(Eigen::Vector2d(1.0, 0.0));
  EXPECT_NEAR(xd.x(), std::atan(1.0), 1e-15);
}

TEST(CameraModelTest, EquidistantJacobianMatchesFiniteDifferencesFromAxisTo85Degrees) {
  const CameraModel camera(Fisheye());
  for (double angle_deg : {0.0, 1e-6, 0.5, 20.0, 45.0, 70.0, 85.0}) {
    const double theta = RadiansFromDegrees(angle_deg);
    for (double azimuth : {0.3, 2.0, 4.4}) {
      const Eigen::Vector3d p(std::sin(theta) * std::cos(azimuth),
                              std::sin(theta) * std::sin(azimuth), std::cos(theta));
      ExpectProjectionJacobianMatches(camera, 0.7 * p);
    }
  }
}

// Every pixel whose ray is less than 90 degrees off-axis comes back to itself; beyond,
// NormalizedFromPixel says it cannot.
TEST(CameraModelTest, EquidistantUndistortionInvertsOverTheImageUpTo90Degrees) {
  const CameraModel camera(Fisheye());
  EXPECT_DOUBLE_EQ(camera.max_field_angle(), std::numbers::pi / 2);  // this lens does not fold
  int inverted = 0, refused = 0;
  double widest_deg = 0;
  for (double u = 0; u <= 1023; u += 31) {
    for (double v = 0; v <= 767; v += 31) {
      const Eigen::Vector2d uv(u, v);
      const double theta_d = Eigen::Vector2d((u - 510.0) / 300.0, (v - 386.0) / 301.0).norm();
      Eigen::Vector2d xn;
      const bool ok = camera.NormalizedFromPixel(uv, &xn);
      EXPECT_TRUE(xn.allFinite());
      const Eigen::Vector2d at_90 = camera.Distort(Eigen::Vector2d(1e9, 0));
      if (theta_d >= at_90.norm()) {
        EXPECT_FALSE(ok) << uv.transpose();
        ++refused;
        continue;
      }
      ASSERT_TRUE(ok) << uv.transpose();
      ++inverted;
      widest_deg = std::max(widest_deg, DegreesFromRadians(std::atan(xn.norm())));
      EXPECT_NEAR((camera.PixelFromNormalized(xn) - uv).norm(), 0.0, 1e-8) << uv.transpose();
    }
  }
  EXPECT_GT(inverted, 300);
  EXPECT_GT(refused, 20);  // the corners
  EXPECT_GT(widest_deg, 88.0);
}

TEST(CameraModelTest, EquidistantUndistortionRefusesPixelsBeyondAFold) {
  CameraIntrinsics folding = Fisheye();
  folding.distortion = Eigen::Vector4d(-0.5, 0, 0, 0);  // theta_d' = 1 - 1.5 theta^2
  const CameraModel camera(folding);
  const double fold = std::sqrt(1 / 1.5);
  EXPECT_NEAR(camera.max_field_angle(), fold, 1e-9);
  const auto pixel_at = [&](double theta) {
    return camera.PixelFromNormalized(Eigen::Vector2d(std::tan(theta), 0));
  };
  Eigen::Vector2d xn;
  ASSERT_TRUE(camera.NormalizedFromPixel(pixel_at(0.95 * fold), &xn));
  EXPECT_NEAR(std::atan(xn.x()), 0.95 * fold, 1e-9);
  // Beyond the fold theta_d decreases: that pixel is also the image of a ray inside it.
  EXPECT_FALSE(camera.NormalizedFromPixel(pixel_at(fold) + Eigen::Vector2d(0.5, 0), &xn));
}

// Issue 27 point 3: `plan` took corners past a lens's fold for corners in the image. The
// radial-tangential model folds where d(r g(r^2))/dr reaches 0: k1 = -5 alone at
// r = 1/sqrt(15) (14.5 deg); before the fix only the equidistant model had a field limit.
TEST(CameraModelTest, RadTanFieldEndsWhereTheRadialMapFolds) {
  CameraIntrinsics folding = Camera(5);
  folding.distortion.setZero();
  folding.distortion[0] = -5.0;
  const CameraModel camera(folding);
  const double fold = std::atan(1 / std::sqrt(15.0));
  EXPECT_NEAR(camera.max_field_angle(), fold, 1e-9);
  // Twice the fold's angle: the polynomial sends it back inside the image, near the centre.
  const Eigen::Vector3d past_fold(std::tan(2 * fold), 0, 1);
  Eigen::Vector2d uv;
  ASSERT_TRUE(camera.Project(past_fold, &uv));
  EXPECT_GT(uv.x(), 0);
  EXPECT_LT(uv.x(), camera.width() - 1);
  EXPECT_FALSE(camera.InValidField(past_fold));
  EXPECT_FALSE(camera.ProjectVisible(past_fold, &uv));
  const Eigen::Vector3d inside(std::tan(0.9 * fold), 0, 1);
  EXPECT_TRUE(camera.InValidField(inside));
  EXPECT_TRUE(camera.ProjectVisible(inside, &uv));
  EXPECT_FALSE(camera.InValidField(Eigen::Vector3d(0, 0, -1)));  // behind the camera
}

// Issue 42 point 19: a distortion fit that folds inside the image was used (a third of the
// image without a valid ray). The fold matters where the image reaches past it: radtan
// k1 -0.8 folds at r = 0.65 (distorted radius 0.43, about 346 px) inside a 1024 x 768 image
// reaching 0.80; k1 -0.2 folds at 52 deg, distorted radius 0.86, beyond the image.
TEST(CameraModelTest, FoldInsideImageSaysWhereALensFoldsWithinTheImage) {
  EXPECT_EQ(CameraModel(Camera(5)).FoldInsideImage(), "");
  EXPECT_EQ(CameraModel(Camera(8)).FoldInsideImage(), "");
  EXPECT_EQ(CameraModel(Fisheye()).FoldInsideImage(), "");
  CameraIntrinsics radtan = Camera(5);
  radtan.distortion.setZero();
  radtan.distortion[0] = -0.8;
  const std::string fold = CameraModel(radtan).FoldInsideImage();
  EXPECT_NE(fold.find("the lens model folds about 346 px from the principal point (32.8 deg off "
                      "the axis) but the image reaches 640 px"),
            std::string::npos)
      << fold;
  radtan.distortion[0] = -0.2;
  ASSERT_LT(CameraModel(radtan).max_field_angle(), 0.95);  // it folds, outside the image
  EXPECT_EQ(CameraModel(radtan).FoldInsideImage(), "");
  CameraIntrinsics fisheye = Fisheye();
  fisheye.distortion = Eigen::Vector4d(-0.5, 0, 0, 0);  // folds at theta_d 0.54: 164 px
  EXPECT_NE(CameraModel(fisheye).FoldInsideImage().find("folds about 164 px"), std::string::npos)
      << CameraModel(fisheye).FoldInsideImage();
}

TEST(CameraModelTest, EquidistantFieldEndsAtTheFoldAndAnUndistortedLensSeesTheHalfSpace) {
  CameraIntrinsics folding = Fisheye();
  folding.distortion = Eigen::Vector4d(-30, 0, 0, 0);  // issue 27: folds at about 6 deg
  const CameraModel fisheye(folding);
  const double fold = std::sqrt(1 / 90.0);
  EXPECT_NEAR(fisheye.max_field_angle(), fold, 1e-9);
  EXPECT_TRUE(fisheye.InValidField(Eigen::Vector3d(std::tan(0.99 * fold), 0, 1)));
  EXPECT_FALSE(fisheye.InValidField(Eigen::Vector3d(0, std::tan(1.01 * fold), 1)));
  const CameraModel pinhole(Camera(0));
  EXPECT_DOUBLE_EQ(pinhole.max_field_angle(), std::numbers::pi / 2);
  EXPECT_TRUE(pinhole.InValidField(Eigen::Vector3d(1e6, 1e6, 1e-3)));
  // An ordinary lens (k1 -0.3, k2 0.1) never folds.
  CameraIntrinsics ordinary = Camera(5);
  ordinary.distortion << -0.3, 0.1, 0.001, -0.001, 0.0;
  EXPECT_DOUBLE_EQ(CameraModel(ordinary).max_field_angle(), std::numbers::pi / 2);
}

TEST(CameraModelTest, UndistortionInvertsDistortionAcrossTheImage) {
  const CameraModel camera(Camera(8));
  for (double u = 0; u <= 1023; u += 170.5) {
    for (double v = 0; v <= 767; v += 127.75) {
      Eigen::Vector2d xn;
      ASSERT_TRUE(camera.NormalizedFromPixel(Eigen::Vector2d(u, v), &xn));
      const Eigen::Vector2d back = camera.PixelFromNormalized(xn);
      EXPECT_NEAR((back - Eigen::Vector2d(u, v)).norm(), 0.0, 1e-8);
    }
  }
}

// A fisheye sees past 90 degrees: over every pixel of Fisheye() (corners ~107 degrees
// off-axis) the ray RayFromPixel gives projects back onto the pixel through ProjectRay, and
// agrees with Project and NormalizedFromPixel where they hold (in front, z > 0).
TEST(CameraModelTest, FisheyeRaysPastNinetyDegreesRoundTripThroughProjectRay) {
  const CameraModel camera(Fisheye());
  ASSERT_GT(camera.max_ray_angle(), std::numbers::pi / 2);
  int behind = 0;
  for (int v = 0; v < 768; v += 17) {
    for (int u = 0; u < 1024; u += 17) {
      const Eigen::Vector2d uv(u, v);
      Eigen::Vector3d ray;
      ASSERT_TRUE(camera.RayFromPixel(uv, &ray)) << uv.transpose();
      EXPECT_NEAR(ray.norm(), 1.0, 1e-12);
      Eigen::Vector2d back;
      ASSERT_TRUE(camera.ProjectRay(2.5 * ray, &back));
      EXPECT_LT((back - uv).norm(), 1e-7) << uv.transpose();
      if (ray.z() <= 0) {
        ++behind;
        continue;
      }
      Eigen::Vector2d uv_project;
      ASSERT_TRUE(camera.Project(ray, &uv_project));
      EXPECT_LT((uv_project - uv).norm(), 1e-7);
    }
  }
  EXPECT_GT(behind, 0) << "no pixel of the test camera sees past 90 degrees";
  // A pinhole lens has no ray at 90 degrees: ProjectRay is ProjectVisible there.
  const CameraModel pinhole(Camera(5));
  Eigen::Vector2d uv;
  EXPECT_FALSE(pinhole.ProjectRay(Eigen::Vector3d(1.0, 0.0, -0.01), &uv));
  EXPECT_DOUBLE_EQ(pinhole.max_ray_angle(), pinhole.max_field_angle());
}

TEST(CameraModelTest, PointBehindCameraIsRefused) {
  const CameraModel camera(Camera(5));
  Eigen::Vector2d uv(-1, -1);
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0.1, 0.1, -0.5), &uv));
  EXPECT_EQ(uv, Eigen::Vector2d(-1, -1));
}

TEST(CameraModelTest, UnsupportedDistortionCountIsInvalid) {
  EXPECT_FALSE(CameraModel(Camera(6)).valid());
  EXPECT_TRUE(CameraModel(Camera(5)).valid());
  CameraIntrinsics fisheye = Fisheye();
  EXPECT_TRUE(CameraModel(fisheye).valid());
  fisheye.distortion = Eigen::VectorXd::Zero(5);  // five coefficients: a radtan vector
  EXPECT_FALSE(CameraModel(fisheye).valid());
}

TEST(CameraModelTest, DistortionModelNamesRoundTrip) {
  for (DistortionModel model : {DistortionModel::kRadTan, DistortionModel::kEquidistant}) {
    EXPECT_EQ(DistortionModelFromName(ToString(model)), model);
  }
  EXPECT_EQ(DistortionModelFromName("fisheye"), std::nullopt);
  EXPECT_EQ(DistortionModelFromName("RadTan"), std::nullopt);
}

}  // namespace
}  // namespace h4
