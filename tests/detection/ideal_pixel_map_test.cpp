// The per-pixel undistortion table for both lens models: every pixel's ideal point maps
// back to the pixel, and the image of a straight line in space (bent by the lens) is
// straight again in ideal coordinates, which is what edge fitting relies on.
#include "firmware/detection/ideal_pixel_map.h"

#include <gtest/gtest.h>

namespace h4::cam {
namespace {

CameraIntrinsics SmallCamera(DistortionModel model) {
  CameraIntrinsics camera = CameraIntrinsics::Pinhole(160, 120, 70.0, 70.5, 81.0, 58.0);
  camera.distortion_model = model;
  if (model == DistortionModel::kEquidistant) {
    camera.distortion = Eigen::Vector4d(0.02, -0.01, 0.003, -0.0005);  // 50 deg at the edges
  } else {
    camera.distortion = Eigen::VectorXd(5);
    camera.distortion << -0.2, 0.05, 0.001, -0.001, 0.0;
  }
  return camera;
}

TEST(IdealPixelMap, EveryPixelMapsBackToItselfForBothLensModels) {
  for (DistortionModel model : {DistortionModel::kRadTan, DistortionModel::kEquidistant}) {
    const IdealPixelMap map{CameraModel(SmallCamera(model))};
    for (int v = 0; v < map.height(); ++v) {
      for (int u = 0; u < map.width(); ++u) {
        const Eigen::Vector2d back = map.PixelFromIdeal(map.At(u, v));
        ASSERT_NEAR((back - Eigen::Vector2d(u, v)).norm(), 0.0, 1e-8)
            << ToString(model) << " pixel " << u << ", " << v;
      }
    }
  }
}

TEST(IdealPixelMap, AStraightLineSeenThroughAFisheyeIsStraightInIdealCoordinates) {
  const CameraModel camera(SmallCamera(DistortionModel::kEquidistant));
  const IdealPixelMap map(camera);
  // A line across the field, 40 degrees off-axis at its ends.
  const Eigen::Vector3d a(-0.8, 0.5, 1.0), b(0.8, 0.45, 1.0);
  std::vector<Eigen::Vector2d> pixels, ideal;
  for (int i = 0; i <= 20; ++i) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(a + (b - a) * i / 20.0, &uv));
    pixels.push_back(uv);
    ideal.push_back(map.IdealFromPixel(uv));
  }
  const auto largest_distance_from_chord = [](const std::vector<Eigen::Vector2d>& points) {
    const Eigen::Vector2d d = (points.back() - points.front()).normalized();
    double largest = 0;
    for (const auto& p : points) {
      const Eigen::Vector2d q = p - points.front();
      largest = std::max(largest, std::abs(q.x() * d.y() - q.y() * d.x()));
    }
    return largest;
  };
  EXPECT_GT(largest_distance_from_chord(pixels), 2.0);  // the lens bends it by pixels
  EXPECT_LT(largest_distance_from_chord(ideal), 1e-8);
}

}  // namespace
}  // namespace h4::cam
