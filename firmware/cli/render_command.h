// `h4cam render --board B.yaml --camera C.yaml --pose x,y,z,qw,qx,qy,qz [--frames N]
// [--noise 2] [--blur 0.8] [--seed S] --out DIR`: synthetic frames of the board at X_CT
// (frame_0000.png, ...), the ground truth for testing `h4cam measure`.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace h4::cam {

struct RenderArgs {
  std::string board_path;
  std::string camera_path;
  std::vector<double> pose;  ///< x, y, z (m), qw, qx, qy, qz: X_CT
  int frames = 1;
  double noise = 2.0;  ///< grey levels
  double blur = 0.8;   ///< px
  uint64_t seed = 1;
  std::string out_dir;
};

void AddRenderCommand(CLI::App& app);

/// Writes the frames; throws (std::runtime_error or h4::FormatError) naming the file or
/// option at fault.
void RunRender(const RenderArgs& args, std::ostream& out);

}  // namespace h4::cam
