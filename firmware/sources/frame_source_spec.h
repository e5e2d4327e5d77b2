// Which frame source a command reads: the text of `--source` (h4cam run, capture, preview)
// and of the service configuration's `source:` key, parsed in this one place.
//   libcamera    the camera module (libcamera_source.h)
//   sim          the synthetic renderer (sim_source.h)
//   dir:PATH     image files: PATH is a file or a folder, read in name order
//                (image_file_source.h)
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace h4::cam {

struct FrameSourceSpec {
  enum class Kind { kLibcamera, kSim, kImageFiles };
  Kind kind = Kind::kLibcamera;
  std::string path;  ///< kImageFiles: the file or folder after "dir:"
};

/// The spec `text` names; nullopt for any other text, with `why` saying what was expected.
std::optional<FrameSourceSpec> ParseFrameSourceSpec(std::string_view text, std::string* why);

}  // namespace h4::cam
