// `h4cam render`; see render_command.h.
#include "firmware/cli/render_command.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/geometry/rotation.h"
#include "firmware/render/board_renderer.h"

namespace h4::cam {
namespace {

/// A flag that overrides one number of the preset: its names, where the parsed value is
/// kept, the RenderOptions field it replaces, its help and its range (render_options.h).
struct PresetOverride {
  const char* names;
  std::optional<double> RenderArgs::*value;
  double RenderOptions::*field;
  const char* what;
  double min, max;
};

// In the order --help lists them.
const PresetOverride kPresetOverrides[] = {
    {"--blur-px,--blur", &RenderArgs::blur_sigma_px, &RenderOptions::blur_sigma_px,
     "Gaussian PSF sigma, px (0..20)", 0.0, 20.0},
    {"--pixel-blur-px", &RenderArgs::pixel_blur_sigma_px, &RenderOptions::pixel_blur_sigma_px,
     "Gaussian blur of the pixel values after integration (an ISP's demosaicing), px (0..20)", 0.0,
     20.0},
    {"--focus-distance", &RenderArgs::focus_distance, &RenderOptions::focus_distance,
     "Defocus: distance the lens is focused at, m (0 = no defocus)", 0.0, 1000.0},
    {"--aperture", &RenderArgs::aperture_diameter, &RenderOptions::aperture_diameter,
     "Defocus: entrance pupil diameter, m (3.8 mm f/2: 0.0019)", 0.0, 0.05},
    {"--gradient", &RenderArgs::illumination_gradient, &RenderOptions::illumination_gradient,
     "Illumination change across the image, fraction (0..1)", 0.0, 1.0},
    {"--gradient-direction", &RenderArgs::illumination_gradient_direction_deg,
     &RenderOptions::illumination_gradient_direction_deg,
     "Direction the light grows in, deg from +u toward +v", -360.0, 360.0},
    {"--vignetting", &RenderArgs::vignetting, &RenderOptions::vignetting,
     "Light lost at the image corners, fraction (0..0.9)", 0.0, 0.9},
    {"--full-well,--shot-noise", &RenderArgs::full_well_electrons,
     &RenderOptions::full_well_electrons,
     "Shot noise: electrons at full scale (0 = none, else 100..1e7)", 0.0, 1e7},
    {"--read-noise,--noise", &RenderArgs::read_noise, &RenderOptions::noise_sigma,
     "Read noise sigma, grey levels of the linear signal (0..50)", 0.0, 50.0},
};

}  // namespace

RenderOptions RenderOptionsFromArgs(const RenderArgs& args) {
  RenderOptions options;
  if (!RenderPresetByName(args.preset, &options)) {
    throw std::invalid_argument("--preset '" + args.preset + "': expected clean or processed");
  }
  for (const PresetOverride& flag : kPresetOverrides) {
    if (const std::optional<double>& value = args.*flag.value) options.*flag.field = *value;
  }
  std::string why;
  if (args.response && !ParseResponseCurve(*args.response, &options, &why)) {
    throw std::invalid_argument("--response: " + why);
  }
  if (!options.IsValid(&why)) throw std::invalid_argument("render options: " + why);
  return options;
}

std::string BoardOutOfView(const BoardSpec& board, const CameraIntrinsics& camera,
                           const RigidTransform& X_CT) {
  const BoardModel model(board);
  const CameraModel projection(camera);
  int in_front = 0;
  for (const Eigen::Vector3d& p_TQ : model.corners()) {
    const Eigen::Vector3d p_CQ = X_CT * p_TQ;
    Eigen::Vector2d uv;
    if (!(p_CQ.z() > 0) && !projection.ProjectRay(p_CQ, &uv)) continue;
    ++in_front;
    // ProjectRay: a fisheye of more than 180 degrees also sees points with z <= 0.
    if (!projection.ProjectRay(p_CQ, &uv)) continue;
    // Pixel centres run from 0 to width - 1 (common/formats/README.md): the image covers
    // [-0.5, width - 0.5).
    if (uv.x() >= -0.5 && uv.x() < camera.width - 0.5 && uv.y() >= -0.5 &&
        uv.y() < camera.height - 0.5) {
      return "";
    }
  }
  return in_front == 0
             ? "the board is behind the camera (no corner has z > 0 in the camera "
               "frame, nor is inside a fisheye's field)"
             : fmt::format("the board is off the image (no corner projects into the {}x{} image)",
                           camera.width, camera.height);
}

bool RunRender(const RenderArgs& args, std::ostream& out) {
  if (args.frames < 1 || args.frames > kMaxRenderFrames) {
    throw std::invalid_argument(
        fmt::format("--frames {}: expected 1..{}", args.frames, kMaxRenderFrames));
  }
  const RenderOptions options = RenderOptionsFromArgs(args);
  const BoardSpec board = ReadBoardYaml(args.board_path);
  const CameraIntrinsics camera = ReadCameraYaml(args.camera_path);
  if (args.pose.size() != 7) {
    throw std::invalid_argument(
        fmt::format("--pose: expected 7 numbers x,y,z,qw,qx,qy,qz, got {}", args.pose.size()));
  }
  Eigen::Matrix3d R_CT;
  if (!RotationFromQuaternion(args.pose[3], args.pose[4], args.pose[5], args.pose[6], &R_CT)) {
    throw std::invalid_argument("--pose: quaternion (qw, qx, qy, qz) must have unit norm");
  }
  const RigidTransform X_CT(R_CT, Eigen::Vector3d(args.pose[0], args.pose[1], args.pose[2]));
  if (const std::string why = BoardOutOfView(board, camera, X_CT); !why.empty()) {
    out << "h4cam render: nothing rendered: " << why << " at --pose\n";
    return false;
  }
  const BoardRenderer renderer(board, camera, options);
  if (!renderer.ok()) throw std::runtime_error(args.board_path + ": " + renderer.error());
  std::filesystem::create_directories(args.out_dir);
  const cv::Mat clean = renderer.RenderClean(X_CT);
  cv::RNG rng(args.seed);
  for (int k = 0; k < args.frames; ++k) {
    const std::string name = fmt::format("frame_{:04}.png", k);
    const std::string path = (std::filesystem::path(args.out_dir) / name).string();
    if (!cv::imwrite(path, renderer.Expose(clean, rng))) {
      throw std::runtime_error(path + ": cannot write the image");
    }
  }
  out << "wrote " << args.frames << " frame(s) " << camera.width << "x" << camera.height << " to "
      << args.out_dir << "\n";
  return true;
}

void DeclareRenderCommand(CLI::App* command) {
  const auto args = std::make_shared<RenderArgs>();
  h4::cli::AddBoardOption(command, &args->board_path)->required();
  h4::cli::AddCameraOption(command, &args->camera_path)->required();
  command->add_option("--pose", args->pose, "X_CT as x,y,z,qw,qx,qy,qz (m, unit quaternion)")
      ->required()
      ->delimiter(',')
      ->expected(7);
  command->add_option("--frames", args->frames, "Number of frames")
      ->default_val(args->frames)
      ->check(CLI::Range(1, kMaxRenderFrames));
  command
      ->add_option("--preset", args->preset,
                   "Image formation: clean (linear, Gaussian blur and noise) or processed "
                   "(a camera module's sRGB output: defocus, gradient, shot noise)")
      ->default_val(args->preset)
      ->check(h4::cli::OneOf(kRenderPresetNames));
  for (const PresetOverride& flag : kPresetOverrides) {
    command->add_option(flag.names, (*args).*flag.value, flag.what)
        ->check(CLI::Range(flag.min, flag.max));
  }
  command->add_option("--response", args->response,
                      "Response curve: linear, srgb, gamma:EXPONENT or table:V0,V1,...");
  h4::cli::AddSeedOption(command, &args->seed, "Noise seed");
  h4::cli::AddOutDirOption(command, &args->out_dir, "Output folder (frame_NNNN.png)", "--out")
      ->required();
  command->footer(
      "Exit codes: 0 frames written, 3 the board is not in view at --pose (behind the "
      "camera or off the image; nothing written), 1 error.");
  h4::cli::RunWhenParsed(command, args, [](const RenderArgs& parsed) {
    return RunRender(parsed, std::cout) ? h4::cli::kExitSuccess : h4::cli::kExitNothingUsable;
  });
}

}  // namespace h4::cam
