// `h4cam render --board B.yaml --camera C.yaml --pose x,y,z,qw,qx,qy,qz [--frames N]
// [--preset clean|processed] [--blur PX] [--focus-distance M --aperture M]
// [--gradient F [--gradient-direction DEG]] [--vignetting F] [--full-well E]
// [--read-noise LEVELS] [--response linear|srgb|gamma:E|table:V,...] [--seed S] --out DIR`:
// synthetic frames of the board at X_CT (frame_0000.png, ...), the ground truth for testing
// `h4cam measure`. The preset gives every value (render_options.h); the flags override it.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "common/board/board_spec.h"
#include "common/camera/camera_intrinsics.h"
#include "common/geometry/rigid_transform.h"
#include "firmware/render/render_options.h"

namespace CLI {
class App;
}

namespace h4::cam {

struct RenderArgs {
  std::string board_path;
  std::string camera_path;
  std::vector<double> pose;  ///< x, y, z (m), qw, qx, qy, qz: X_CT
  int frames = 1;
  /// clean | processed (render_options.h); processed, as `capture` and `run --source sim`.
  std::string preset = "processed";
  // Overrides of the preset's values, unset = the preset's (units: render_options.h).
  std::optional<double> blur_sigma_px, pixel_blur_sigma_px, focus_distance, aperture_diameter;
  std::optional<double> illumination_gradient, illumination_gradient_direction_deg;
  std::optional<double> vignetting, full_well_electrons, read_noise;
  std::optional<std::string> response;  ///< linear | srgb | gamma:E | table:V0,V1,...
  uint64_t seed = 1;
  std::string out_dir;
};

/// Most frames one call writes.
constexpr int kMaxRenderFrames = 1000;

void DeclareRenderCommand(CLI::App* command);

/// The preset with the flags applied; throws std::invalid_argument naming the option at
/// fault (unknown preset, malformed response, or values out of range).
RenderOptions RenderOptionsFromArgs(const RenderArgs& args);

/// Why the board at X_CT would not be seen by the camera: "" when at least one of its
/// corners projects into the image; else it is behind the camera (no corner in front of
/// it) or off the image (in front, but every corner outside the image).
std::string BoardOutOfView(const BoardSpec& board, const CameraIntrinsics& camera,
                           const RigidTransform& X_CT);

/// Writes the frames and returns true; returns false, writing nothing, when the board is
/// not in view (BoardOutOfView, said on `out`). Throws std::invalid_argument naming the
/// option at fault, h4::FormatError naming the file, std::runtime_error when an image
/// cannot be written.
bool RunRender(const RenderArgs& args, std::ostream& out);

}  // namespace h4::cam
