// Fuzz target: the camera intrinsics reader (OpenCV FileStorage YAML and Kalibr camchain,
// as a whole file and as camera cam1 of it); what it accepts must stay within the size
// limits, write (as OpenCV YAML) and read back with the same values, and give a camera
// model whose valid field (where a projection decides visibility) is an angle in [0, pi/2].
#include <numbers>

#include "common/camera/camera_model.h"
#include "common/formats/camera_yaml.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

void CheckAccepted(const h4::CameraIntrinsics& camera) {
  using namespace h4;
  fuzz::Require(camera.width >= 1 && camera.height >= 1 && camera.width <= kMaxImageSide_px &&
                    camera.height <= kMaxImageSide_px &&
                    int64_t{camera.width} * camera.height <= kMaxImagePixels,
                "an accepted camera is within the size limits");
  const CameraIntrinsics back = ParseCameraYaml(FormatCameraYaml(camera), "written.yaml");
  fuzz::Require(back.width == camera.width && back.height == camera.height && back.K == camera.K &&
                    back.distortion_model == camera.distortion_model &&
                    back.distortion == camera.distortion &&
                    back.avg_reprojection_error == camera.avg_reprojection_error,
                "camera YAML round trip keeps the values");
  // Computed once in the constructor by a bounded scan, whatever the coefficients (issue 27
  // point 3: a lens that folds at 6 deg).
  const CameraModel model(camera);
  const double field = model.max_field_angle();
  fuzz::Require(field >= 0 && field <= std::numbers::pi / 2,
                "the camera model's valid field is an angle in [0, pi/2]");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace h4;
  const std::string text = fuzz::Text(data, size);
  for (const char* kalibr_camera : {"", "cam1"}) {
    const auto camera = fuzz::ParseOrRefuse(text, [kalibr_camera](const std::string& t) {
      return ParseCameraYaml(t, "c.yaml", kalibr_camera);
    });
    if (camera) CheckAccepted(*camera);
  }
  return 0;
}
