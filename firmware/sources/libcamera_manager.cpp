// Shared libcamera CameraManager and camera listing (see libcamera_manager.h).
#include "firmware/sources/libcamera_manager.h"

#include <cstdlib>
#include <mutex>

#include <fmt/format.h>
#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>

#include "firmware/sources/libcamera_compat.h"

namespace h4::cam {

std::shared_ptr<libcamera::CameraManager> SharedCameraManager(std::string* error) {
  static std::mutex mutex;
  static std::weak_ptr<libcamera::CameraManager> shared;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = shared.lock()) return existing;

  // overwrite = 0: a user who set the variable keeps their levels.
  setenv("LIBCAMERA_LOG_LEVELS", "*:ERROR", 0);
  // ~CameraManager stops it, so the last shared_ptr to go stops the camera stack.
  auto manager = std::make_shared<libcamera::CameraManager>();
  if (const int ret = manager->start(); ret != 0) {
    *error = fmt::format(
        "libcamera: camera manager failed to start (error {}); is the camera stack (libcamera "
        "{}) installed?",
        -ret, compat::CompiledLibcameraVersion());
    return nullptr;
  }
  shared = manager;
  return manager;
}

bool ListCameras(std::vector<CameraInfo>* cameras, std::string* error) {
  cameras->clear();
  auto manager = SharedCameraManager(error);
  if (!manager) return false;
  for (const auto& camera : manager->cameras()) {
    cameras->push_back({camera->id(), compat::CameraModel(*camera).value_or("")});
  }
  return true;
}

}  // namespace h4::cam
