// The frame source of a spec; see make_frame_source.h.
#include "firmware/sources/make_frame_source.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "firmware/sources/image_file_source.h"

namespace h4::cam {

std::unique_ptr<FrameSource> MakeFrameSource(const FrameSourceSpec& spec,
                                             const FrameSourceParts& parts) {
  switch (spec.kind) {
    case FrameSourceSpec::Kind::kSim:
      if (parts.board == nullptr || parts.rendered_camera == nullptr) {
        throw std::invalid_argument("sim source: no board or camera to render");
      }
      return std::make_unique<SimSource>(*parts.board, *parts.rendered_camera, parts.sim);
    case FrameSourceSpec::Kind::kImageFiles:
      return std::make_unique<ImageFileSource>(std::vector<std::string>{spec.path});
    case FrameSourceSpec::Kind::kLibcamera:
      break;
  }
  return std::make_unique<LibcameraSource>(parts.libcamera);
}

}  // namespace h4::cam
