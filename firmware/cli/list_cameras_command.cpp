// `h4cam list-cameras`; see list_cameras_command.h.
#include "firmware/cli/list_cameras_command.h"

#include <ostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "firmware/sources/libcamera_compat.h"
#include "firmware/sources/libcamera_manager.h"

namespace h4::cam {

int RunListCameras(std::ostream& out) {
  std::vector<CameraInfo> cameras;
  std::string error;
  if (!ListCameras(&cameras, &error)) throw std::runtime_error(error);
  if (cameras.empty()) {
    out << "no cameras found (libcamera " << compat::CompiledLibcameraVersion()
        << " sees no camera: is one connected and enabled?)\n";
    return 0;
  }
  for (const auto& camera : cameras) {
    out << camera.id << (camera.model.empty() ? "" : "  " + camera.model) << "\n";
  }
  return 0;
}

void DeclareListCamerasCommand(CLI::App* command) {
  command->callback([] {
    if (const int code = RunListCameras(std::cout); code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace h4::cam
