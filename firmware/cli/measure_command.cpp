// `h4cam measure`; see measure_command.h.
#include "firmware/cli/measure_command.h"

#include <iostream>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_poses_csv.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "common/formats/file_output.h"
#include "firmware/cli/frame_check.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/sources/image_file_source.h"

namespace h4::cam {

namespace {

/// What `measure` writes: a row per group of images, the corners of the groups with a pose.
struct MeasureOutputs {
  std::vector<BoardPoseRow> rows;
  std::vector<h4::CornerObservation> corner_rows;
  int with_pose = 0;

  /// Adds the measurement of one group and prints its line ("[k/groups] image: status").
  void Record(const Measurement& m, size_t groups, std::ostream& progress) {
    BoardPoseRow row;
    row.image = m.origin;
    row.corners = m.corners_used;
    if (m.ok()) {
      row.X_CT = m.X_CT;
      row.rms_px = m.rms_px;
      row.sigma_t = m.sigma_t;
      row.sigma_r = m.sigma_r;
      ++with_pose;
      // The pose id is the row's number in --out (common/formats/README.md#board-corners-csv).
      const std::vector<h4::CornerObservation> used =
          CornerRows(m, static_cast<int64_t>(rows.size()));
      corner_rows.insert(corner_rows.end(), used.begin(), used.end());
    }
    rows.push_back(row);
    progress << "[" << rows.size() << "/" << groups << "] " << m.origin << ": "
             << ToString(m.status);
    if (m.ok()) {
      const Eigen::Vector3d& p = m.X_CT.translation();
      // As many digits as the figures hold (issue 43 point 8: they printed 7).
      progress << fmt::format(", {} corners, rms {:.4f} px, z {:.4f} m, sigma_t {:.4f} mm",
                              m.corners_used, m.rms_px, p.z(), m.sigma_t * 1e3);
    } else if (!m.message.empty()) {
      progress << " (" << m.message << ")";
    }
    progress << "\n";
  }
};

/// Groups of `group` images (the last one may be short), said when they do not divide.
size_t GroupCount(size_t images, int group, std::ostream& progress) {
  const auto per_group = static_cast<size_t>(group);
  if (images % per_group != 0) {
    progress << "note: " << images << " images do not fill groups of " << group
             << "; the last group averages " << images % per_group << "\n";
  }
  return (images + per_group - 1) / per_group;
}

/// Throws std::runtime_error naming the first image whose header is unreadable, out of the
/// size limits, or of another size than the camera file's.
void RequireTheCameraFilesSizeInHeaders(const std::vector<std::string>& files,
                                        const CameraIntrinsics& camera,
                                        const std::string& camera_path) {
  for (const std::string& path : files) {
    std::string why;
    const std::optional<ImageHeaderSize> size = ImageFileSource::HeaderSize(path, &why);
    if (!size) throw std::runtime_error(why);
    if (size->width != camera.width || size->height != camera.height) {
      throw std::runtime_error(fmt::format("{}: image is {}x{}, the camera file {} says {}x{}",
                                           path, size->width, size->height, camera_path,
                                           camera.width, camera.height));
    }
  }
}

}  // namespace

int RunMeasure(const MeasureArgs& args, std::ostream& progress) {
  if (!args.corners_out_path.empty()) {
    RequireOutputIsNotAnInput(
        {"--corners-out", args.corners_out_path},
        {{"--out", args.out_path}, {"--board", args.board_path}, {"--camera", args.camera_path}});
  }
  const BoardSpec board = ReadBoardYaml(args.board_path);
  const CameraIntrinsics camera = ReadCameraYaml(args.camera_path);
  ImageFileSource source(args.images);
  if (!source.Open()) throw std::runtime_error(source.error());
  // Every image's size from its header, before the pipeline sizes its maps from the camera
  // (a 4096 x 4096 camera file took 5.5 s before a 1024 x 768 image was refused, issue 42).
  RequireTheCameraFilesSizeInHeaders(source.files(), camera, args.camera_path);
  PipelineOptions options;
  options.frames = args.group;
  options.motion.max_spread_px = args.max_spread_px;
  MeasurePipeline pipeline(board, camera, options);
  if (!pipeline.ok()) throw std::runtime_error(args.board_path + ": " + pipeline.error());
  const size_t groups = GroupCount(source.files().size(), args.group, progress);
  MeasureOutputs out;
  while (!source.finished()) {
    std::optional<Frame> frame = source.Next(std::chrono::milliseconds(0));
    if (!frame) {
      if (!source.error().empty()) throw std::runtime_error(source.error());
      continue;
    }
    RequireTheCameraFilesSize(*frame, camera, args.camera_path);
    if (std::optional<Measurement> m = pipeline.AddFrame(*frame)) {
      if (m->status == Measurement::Status::kCameraError) throw std::runtime_error(m->message);
      out.Record(*m, groups, progress);
    }
  }
  if (out.rows.size() < groups) out.Record(pipeline.Finish(), groups, progress);
  WriteBoardPosesCsv(args.out_path, out.rows);
  progress << "wrote " << out.rows.size() << " row(s), " << out.with_pose << " with a pose, to "
           << args.out_path << "\n";
  if (!args.corners_out_path.empty()) {
    WriteCornersCsv(args.corners_out_path, out.corner_rows);
    progress << "wrote " << out.corner_rows.size() << " corner(s) to " << args.corners_out_path
             << "\n";
  }
  return out.with_pose;
}

void DeclareMeasureCommand(CLI::App* command) {
  const auto args = std::make_shared<MeasureArgs>();
  h4::cli::AddBoardOption(command, &args->board_path)->required();
  h4::cli::AddCameraOption(command, &args->camera_path)->required();
  h4::cli::AddFramesOption(command, &args->group, "Images averaged per measurement", "--group")
      ->default_val(args->group)
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--max-spread-px,--max-spread", args->max_spread_px,
                   "Motion threshold: largest per-frame corner spread in a group, px")
      ->default_val(args->max_spread_px)
      ->check(CLI::PositiveNumber);
  h4::cli::AddOutOption(command, &args->out_path, "Output CSV (image,x,y,z,qw,qx,qy,qz,...)");
  command->add_option("--corners-out", args->corners_out_path,
                      "Also write the refined corners of each pose: CSV "
                      "pose_id,tag_id,corner,u,v,sigma_px (pose_id: the row's number in --out, "
                      "from 0)");
  command->add_option("images", args->images, "Image files or directories, in order")->required();
  command->footer(
      "Exit codes: 0 at least one row has a pose, 3 no image showed the board (the rows are "
      "written, without poses), 1 error.");
  h4::cli::RunWhenParsed(command, args, [](const MeasureArgs& parsed) {
    if (RunMeasure(parsed, std::cerr) > 0) return h4::cli::kExitSuccess;
    std::cerr << "h4cam measure: no image shows the board " << parsed.board_path
              << ": nothing usable measured\n";
    return h4::cli::kExitNothingUsable;
  });
}

}  // namespace h4::cam
