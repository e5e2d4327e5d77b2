// `h4cam render`; see render_command.h.
#include "firmware/cli/render_command.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/geometry/rotation.h"
#include "firmware/render/board_renderer.h"

namespace h4::cam {

void RunRender(const RenderArgs& args, std::ostream& out) {
  const BoardSpec board = ReadBoardYaml(args.board_path);
  const CameraIntrinsics camera = ReadCameraYaml(args.camera_path);
  if (args.pose.size() != 7) {
    throw std::runtime_error("--pose: expected 7 numbers x,y,z,qw,qx,qy,qz, got " +
                             std::to_string(args.pose.size()));
  }
  Eigen::Matrix3d R_CT;
  if (!RotationFromQuaternion(args.pose[3], args.pose[4], args.pose[5], args.pose[6], &R_CT)) {
    throw std::runtime_error("--pose: quaternion (qw, qx, qy, qz) must have unit norm");
  }
  const RigidTransform X_CT(R_CT, Eigen::Vector3d(args.pose[0], args.pose[1], args.pose[2]));
  RenderOptions options;
  options.noise_sigma = args.noise;
  options.blur_sigma_px = args.blur;
  const BoardRenderer renderer(board, camera, options);
  if (!renderer.ok()) throw std::runtime_error(args.board_path + ": " + renderer.error());
  std::filesystem::create_directories(args.out_dir);
  const cv::Mat clean = renderer.RenderClean(X_CT);
  cv::RNG rng(args.seed);
  for (int k = 0; k < args.frames; ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.png", k);
    const std::string path = (std::filesystem::path(args.out_dir) / name).string();
    if (!cv::imwrite(path, renderer.Expose(clean, rng))) {
      throw std::runtime_error(path + ": cannot write the image");
    }
  }
  out << "wrote " << args.frames << " frame(s) " << camera.width << "x" << camera.height << " to "
      << args.out_dir << "\n";
}

void AddRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* command =
      app.add_subcommand("render", "Synthetic camera frames of the board at a known pose X_CT");
  command->add_option("--board", args->board_path, "Board YAML")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--camera", args->camera_path, "Camera intrinsics YAML (OpenCV)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--pose", args->pose, "X_CT as x,y,z,qw,qx,qy,qz (m, unit quaternion)")
      ->required()
      ->delimiter(',')
      ->expected(7);
  command->add_option("--frames", args->frames, "Number of frames")
      ->default_val(args->frames)
      ->check(CLI::PositiveNumber);
  command->add_option("--noise", args->noise, "Sensor noise sigma, grey levels")
      ->default_val(args->noise)
      ->check(CLI::NonNegativeNumber);
  command->add_option("--blur", args->blur, "Optical blur sigma, px")
      ->default_val(args->blur)
      ->check(CLI::NonNegativeNumber);
  command->add_option("--seed", args->seed, "Noise seed")->default_val(args->seed);
  command->add_option("--out", args->out_dir, "Output directory")->required();
  command->callback([args] { RunRender(*args, std::cout); });
}

}  // namespace h4::cam
