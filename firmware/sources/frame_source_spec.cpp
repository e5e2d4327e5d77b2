// See frame_source_spec.h.
#include "firmware/sources/frame_source_spec.h"

namespace h4::cam {

std::optional<FrameSourceSpec> ParseFrameSourceSpec(std::string_view text, std::string* why) {
  constexpr std::string_view kFilesPrefix = "dir:";
  if (text == "libcamera") return FrameSourceSpec{FrameSourceSpec::Kind::kLibcamera, ""};
  if (text == "sim") return FrameSourceSpec{FrameSourceSpec::Kind::kSim, ""};
  if (text.starts_with(kFilesPrefix)) {
    if (text.size() > kFilesPrefix.size()) {
      return FrameSourceSpec{FrameSourceSpec::Kind::kImageFiles,
                             std::string(text.substr(kFilesPrefix.size()))};
    }
    if (why) *why = "source 'dir:' names no folder";
    return std::nullopt;
  }
  if (why) *why = "source '" + std::string(text) + "': expected libcamera, sim or dir:PATH";
  return std::nullopt;
}

}  // namespace h4::cam
