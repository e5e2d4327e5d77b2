// See real_frames_helpers.h.
#include "tests/calibration/real_frames_helpers.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace h4::cam {

std::string RealFramesDir() {
  std::vector<std::string> roots;
  if (const char* env = std::getenv("H4_REAL_FRAMES_DIR")) roots.emplace_back(env);
  roots.push_back(std::string(H4_SOURCE_DIR) + "/tests/data/real_frames");
  for (const std::string& root : roots) {
    if (std::filesystem::is_directory(root + "/" + kRealFrameSet)) {
      return root + "/" + kRealFrameSet;
    }
  }
  return "";
}

}  // namespace h4::cam
