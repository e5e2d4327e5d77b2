// The process's one libcamera CameraManager. libcamera aborts when two CameraManagers
// exist at once, and list-cameras, the frame source and its restarts each need one, so
// they share this instance; it is stopped when the last user lets go.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace libcamera {
class CameraManager;
}

namespace h4::cam {

/// The shared, started CameraManager, or nullptr with `error` set when it fails to start.
/// Before creating it, sets LIBCAMERA_LOG_LEVELS=*:ERROR unless the user set that variable
/// (without /dev/media* libcamera otherwise warns on every start).
std::shared_ptr<libcamera::CameraManager> SharedCameraManager(std::string* error);

struct CameraInfo {
  std::string id;     ///< libcamera's id, what --camera takes
  std::string model;  ///< sensor model ("imx219"), empty when unknown
};

/// Every camera libcamera sees (empty on a machine without one); false with `error` set
/// only when the camera manager fails to start.
bool ListCameras(std::vector<CameraInfo>* cameras, std::string* error);

}  // namespace h4::cam
