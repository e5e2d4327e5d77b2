// Names and coefficient counts of the distortion models; see camera_intrinsics.h.
#include "common/camera/camera_intrinsics.h"

#include <algorithm>
#include <vector>

namespace h4 {

namespace {

/// What the camera YAML knows of a distortion model (common/formats/README.md): its name,
/// the coefficient counts it accepts (0: no distortion) and how an error message names them.
struct DistortionModelFacts {
  DistortionModel model;
  const char* name;
  std::vector<Eigen::Index> counts;
  const char* expected_counts;
};

const std::vector<DistortionModelFacts>& AllDistortionModelFacts() {
  static const std::vector<DistortionModelFacts> facts = {
      {DistortionModel::kRadTan, "radtan", {0, 4, 5, 8}, "4, 5 or 8 (k1 k2 p1 p2 [k3 [k4 k5 k6]])"},
      {DistortionModel::kEquidistant, "equidistant", {0, 4}, "4 (k1 k2 k3 k4)"},
  };
  return facts;
}

const DistortionModelFacts* FactsOfDistortionModel(DistortionModel model) {
  for (const DistortionModelFacts& facts : AllDistortionModelFacts()) {
    if (facts.model == model) return &facts;
  }
  return nullptr;
}

}  // namespace

const char* ToString(DistortionModel model) {
  const DistortionModelFacts* facts = FactsOfDistortionModel(model);
  return facts ? facts->name : "unknown";
}

std::optional<DistortionModel> DistortionModelFromName(const std::string& name) {
  for (const DistortionModelFacts& facts : AllDistortionModelFacts()) {
    if (name == facts.name) return facts.model;
  }
  return std::nullopt;
}

bool IsSupportedDistortionCount(DistortionModel model, Eigen::Index count) {
  const DistortionModelFacts* facts = FactsOfDistortionModel(model);
  return facts && std::ranges::find(facts->counts, count) != facts->counts.end();
}

std::string ExpectedDistortionCoefficients(DistortionModel model) {
  const DistortionModelFacts* facts = FactsOfDistortionModel(model);
  return facts ? facts->expected_counts : "";
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
