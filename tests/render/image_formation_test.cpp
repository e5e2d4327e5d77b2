// Tests for firmware/render/image_formation: the light field, the defocus disk and the
// sensor (quantisation through the response curve, saturation, shot + read noise), each
// measured on images against the model's formulas.
#include "firmware/render/image_formation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace h4::cam {
namespace {

RenderOptions Noiseless() {
  RenderOptions options;
  options.noise_sigma = 0;
  return options;
}

cv::Mat Uniform(double linear) { return cv::Mat(200, 300, CV_32F, cv::Scalar(linear)); }

TEST(ImageFormationTest, SrgbSensorEncodesLinearLevelsAsTheCurveSays) {
  RenderOptions options = Noiseless();
  options.response = ResponseCurve::kSrgb;
  const SensorModel sensor(options);
  cv::RNG rng(1);
  // Linear mid-grey encodes to 0.7354 of full scale: code 188 (a linear camera: 128).
  EXPECT_EQ(sensor.Expose(Uniform(127.5), rng).at<uint8_t>(10, 10), 188);
  // 18 % grey: 0.4614 -> 118; in the linear toe, 0.002 -> 12.92 * 0.002 -> code 7.
  EXPECT_EQ(sensor.Expose(Uniform(0.18 * 255), rng).at<uint8_t>(10, 10), 118);
  EXPECT_EQ(sensor.Expose(Uniform(0.002 * 255), rng).at<uint8_t>(10, 10), 7);
  options.response = ResponseCurve::kLinear;
  EXPECT_EQ(SensorModel(options).Expose(Uniform(127.6), rng).at<uint8_t>(10, 10), 128);
}

TEST(ImageFormationTest, SignalAboveFullScaleClipsAt255WhateverTheCurve) {
  for (const ResponseCurve curve : {ResponseCurve::kLinear, ResponseCurve::kSrgb}) {
    RenderOptions options;
    options.response = curve;
    options.full_well_electrons = 6000;
    options.noise_sigma = 1.0;
    cv::RNG rng(3);
    const cv::Mat frame = SensorModel(options).Expose(Uniform(300), rng);
    double lo = 0, hi = 0;
    cv::minMaxLoc(frame, &lo, &hi);
    EXPECT_EQ(lo, 255.0);
    cv::minMaxLoc(SensorModel(options).Expose(Uniform(-20), rng), &lo, &hi);
    EXPECT_EQ(hi, 0.0);
  }
}

// Variance of the 8-bit frame of a uniform linear level S: read^2 + S * 255 / full_well
// (shot noise in grey levels) + 1/12 (rounding).
TEST(ImageFormationTest, ShotNoiseVarianceGrowsWithTheSignalAsModelled) {
  RenderOptions options;
  options.full_well_electrons = 5000;
  options.noise_sigma = 1.0;
  const SensorModel sensor(options);
  cv::RNG rng(11);
  std::vector<double> variances;
  for (const double level : {20.0, 80.0, 200.0}) {
    cv::Mat frame;
    sensor.Expose(Uniform(level), rng).convertTo(frame, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(frame, mean, stddev);
    const double model = 1.0 + level * 255 / 5000 + 1.0 / 12;
    EXPECT_NEAR(mean[0], level, 0.05);
    EXPECT_NEAR(stddev[0] * stddev[0], model, 0.04 * model) << "level " << level;
    variances.push_back(stddev[0] * stddev[0]);
  }
  EXPECT_GT(variances[2], 4 * variances[0]);
}

TEST(ImageFormationTest, ReadNoiseAloneIsTheHistoricalGaussian) {
  RenderOptions options;  // clean: Gaussian 2 grey levels, no shot noise
  cv::RNG a(5), b(5);
  const cv::Mat frame = SensorModel(options).Expose(Uniform(100), a);
  cv::Mat noise(200, 300, CV_32F);
  b.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  cv::Mat expected;
  cv::Mat(Uniform(100) + noise).convertTo(expected, CV_8U);
  EXPECT_EQ(cv::norm(frame, expected, cv::NORM_INF), 0.0);
}

TEST(ImageFormationTest, LightIsOneAtTheCentreAndFallsByTheVignettingAtTheCorners) {
  RenderOptions options;
  options.vignetting = 0.3;
  const Illumination light(options, 101, 81);
  EXPECT_FALSE(light.uniform());
  EXPECT_NEAR(light.At(50, 40), 1.0, 1e-12);
  EXPECT_NEAR(light.At(0, 0), 0.7, 1e-12);
  EXPECT_NEAR(light.At(100, 80), 0.7, 1e-12);
  EXPECT_GT(light.At(50, 0), 0.7);
  EXPECT_TRUE(Illumination(RenderOptions{}, 101, 81).uniform());
}

TEST(ImageFormationTest, GradientChangesTheLightByTheFractionAcrossTheImage) {
  RenderOptions options;
  options.illumination_gradient = 0.2;
  options.illumination_gradient_direction_deg = 90;  // brighter downwards
  const Illumination light(options, 100, 80);
  // Pixel edges v = -0.5 and 79.5 are the image's ends: 0.9 and 1.1.
  EXPECT_NEAR(light.At(30, -0.5), 0.9, 1e-12);
  EXPECT_NEAR(light.At(70, 79.5), 1.1, 1e-12);
  EXPECT_NEAR(light.At(0, 39.5), 1.0, 1e-12);
}

TEST(ImageFormationTest, DefocusDiskGrowsWithTheInverseDepthOffset) {
  RenderOptions options;
  options.focus_distance = 0.5;
  options.aperture_diameter = 2e-3;
  EXPECT_DOUBLE_EQ(DefocusRadiusPx(options, 800, 0.5), 0.0);
  // 1 mm half-aperture x 800 px x |1/0.4 - 1/0.5| = 0.4 px.
  EXPECT_NEAR(DefocusRadiusPx(options, 800, 0.4), 0.4, 1e-12);
  EXPECT_NEAR(DefocusRadiusPx(options, 800, 1.0), 0.8, 1e-12);
  options.focus_distance = 0;
  EXPECT_EQ(DefocusRadiusPx(options, 800, 0.4), 0.0);
}

// A uniform disk of radius R has variance R^2 / 4 per axis (a Gaussian of the same
// width would put weight far outside R: the disk has none).
TEST(ImageFormationTest, PillboxKernelIsAUniformDisk) {
  const double radius = 6.0;
  const cv::Mat kernel = PillboxKernel(radius);
  EXPECT_NEAR(cv::sum(kernel)[0], 1.0, 1e-6);
  const int half = kernel.rows / 2;
  double variance_x = 0, outside = 0;
  for (int r = 0; r < kernel.rows; ++r) {
    for (int c = 0; c < kernel.cols; ++c) {
      const double x = c - half, y = r - half, w = kernel.at<float>(r, c);
      variance_x += w * x * x;
      if (std::hypot(x, y) > radius + 0.75) outside += w;
    }
  }
  EXPECT_NEAR(variance_x, radius * radius / 4, 0.03 * radius * radius / 4);
  EXPECT_EQ(outside, 0.0);
  EXPECT_NEAR(kernel.at<float>(half, half), kernel.at<float>(half, half + 3), 1e-7);  // flat
  EXPECT_EQ(PillboxKernel(0.3).total(), 1u);
}

}  // namespace
}  // namespace h4::cam
