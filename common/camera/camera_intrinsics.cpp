// Names and coefficient counts of the distortion models; see camera_intrinsics.h.
#include "common/camera/camera_intrinsics.h"

namespace h4 {

const char* ToString(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadTan:
      return "radtan";
    case DistortionModel::kEquidistant:
      return "equidistant";
  }
  return "unknown";
}

std::optional<DistortionModel> DistortionModelFromName(const std::string& name) {
  for (DistortionModel model : {DistortionModel::kRadTan, DistortionModel::kEquidistant}) {
    if (name == ToString(model)) return model;
  }
  return std::nullopt;
}

bool IsSupportedDistortionCount(DistortionModel model, Eigen::Index count) {
  switch (model) {
    case DistortionModel::kRadTan:
      return count == 0 || count == 4 || count == 5 || count == 8;
    case DistortionModel::kEquidistant:
      return count == 0 || count == 4;
  }
  return false;
}

std::string ExpectedDistortionCoefficients(DistortionModel model) {
  switch (model) {
    case DistortionModel::kRadTan:
      return "4, 5 or 8 (k1 k2 p1 p2 [k3 [k4 k5 k6]])";
    case DistortionModel::kEquidistant:
      return "4 (k1 k2 k3 k4)";
  }
  return "";
}

CameraIntrinsics CameraIntrinsics::Pinhole(int width, int height, double fx, double fy, double cx,
                                           double cy) {
  CameraIntrinsics camera;
  camera.width = width;
  camera.height = height;
  camera.K << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return camera;
}

}  // namespace h4
