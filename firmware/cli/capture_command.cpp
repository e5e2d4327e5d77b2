// `h4cam capture` and `h4cam preview`; see capture_command.h.
#include "firmware/cli/capture_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "common/board/board_model.h"
#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/stop_signal.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/geometry/rotation.h"
#include "firmware/cli/frame_check.h"
#include "firmware/sources/frame_source_spec.h"
#include "firmware/sources/libcamera_source.h"
#include "firmware/sources/make_frame_source.h"
#include "firmware/sources/sim_capture_poses.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {
namespace {

namespace fs = std::filesystem;

/// The board centred on the optical axis, facing the camera, `depth` m away.
RigidTransform CentredBoardPose(const BoardSpec& board, double depth) {
  const BoardModel model(board);
  const Eigen::Vector2d centre = 0.5 * (model.pattern_min() + model.pattern_max());
  return RigidTransform(Eigen::Matrix3d::Identity(),
                        Eigen::Vector3d(-centre.x(), -centre.y(), depth));
}

RigidTransform SimPose(const CaptureArgs& args, const BoardSpec& board) {
  if (args.sim_pose.empty()) return CentredBoardPose(board, 0.5);
  if (args.sim_pose.size() != 7) {
    throw std::invalid_argument(fmt::format(
        "--sim-pose: expected 7 numbers x,y,z,qw,qx,qy,qz, got {}", args.sim_pose.size()));
  }
  const std::vector<double>& v = args.sim_pose;
  Eigen::Matrix3d R_CT;
  if (!RotationFromQuaternion(v[3], v[4], v[5], v[6], &R_CT)) {
    throw std::invalid_argument("--sim-pose: quaternion (qw, qx, qy, qz) must have unit norm");
  }
  return RigidTransform(R_CT, Eigen::Vector3d(v[0], v[1], v[2]));
}

/// sim: the preset's image formation, in more or less light (--sim-exposure).
SimSourceOptions SimOptionsOf(const CaptureArgs& args) {
  SimSourceOptions options;
  if (!RenderPresetByName(args.sim_preset, &options.render)) {
    throw std::invalid_argument("--sim-preset '" + args.sim_preset +
                                "': expected clean or processed");
  }
  // More light on the same print and background: the levels scale, the white clips at 255.
  options.render.black_level *= args.sim_exposure;
  options.render.white_level *= args.sim_exposure;
  options.render.background_level *= args.sim_exposure;
  std::string why;
  if (!options.render.IsValid(&why)) throw std::invalid_argument("--sim-exposure: " + why);
  return options;
}

/// libcamera: the stream of the camera file's size, exposure as asked.
LibcameraSourceOptions LibcameraOptionsOf(const CaptureArgs& args, const CameraIntrinsics& camera) {
  LibcameraSourceOptions options;
  options.camera_id = args.camera_id;
  options.width = camera.width;
  options.height = camera.height;
  options.auto_exposure = args.exposure_us <= 0;
  options.exposure_time = std::chrono::microseconds(static_cast<int64_t>(args.exposure_us));
  options.analogue_gain = static_cast<float>(args.analogue_gain);
  return options;
}

void StartSource(FrameSource& source) {
  if (!source.Open() || !source.Configure() || !source.Start()) {
    throw std::runtime_error(source.Describe() + ": " + source.error());
  }
}

void WritePng(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) {
    throw std::runtime_error(path.string() + ": cannot write the image");
  }
}

/// Writes `image` to `path` through a file beside it, renamed over it: a viewer that
/// reloads the file never sees half of it.
void ReplacePng(const fs::path& path, const cv::Mat& image) {
  const fs::path temporary = path.parent_path() / ("." + path.stem().string() + "-new.png");
  WritePng(temporary, image);
  fs::rename(temporary, path);
}

std::string Numbered(const char* stem, int index) {
  return fmt::format("{}_{:04}.png", stem, index);
}

/// The folder's file names (none when it does not exist yet).
std::vector<std::string> FileNamesIn(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::is_directory(dir)) return names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  return names;
}

/// The source --source names. A sim source shows the board at --sim-pose; saving frames
/// without --sim-pose, it shows capture's pose sequence instead (sim_capture_poses.h), so
/// that the intrinsics step can be rehearsed: it is then returned in `pose_sequence_sim`
/// too, for the caller to pose frame by frame.
std::unique_ptr<FrameSource> MakeCaptureSource(const CaptureArgs& args, bool save_frames,
                                               const BoardSpec& board,
                                               const CameraIntrinsics& camera,
                                               SimSource** pose_sequence_sim) {
  *pose_sequence_sim = nullptr;
  std::string why;
  const std::optional<FrameSourceSpec> spec = ParseFrameSourceSpec(args.source, &why);
  if (!spec) throw std::invalid_argument("--" + why);
  FrameSourceParts parts;
  parts.libcamera = LibcameraOptionsOf(args, camera);
  if (spec->kind != FrameSourceSpec::Kind::kSim) return MakeFrameSource(*spec, parts);
  parts.board = &board;
  parts.rendered_camera = &camera;
  parts.sim = SimOptionsOf(args);
  std::unique_ptr<FrameSource> source = MakeFrameSource(*spec, parts);
  auto* sim = static_cast<SimSource*>(source.get());
  if (save_frames && args.sim_pose.empty()) {
    *pose_sequence_sim = sim;
  } else {
    sim->SetPose(SimPose(args, board));
  }
  return source;
}

/// What is done with one frame: checked, printed, saved and drawn as asked; `index` is its
/// number, in the printed line and the file names.
void TakeFrame(const CaptureArgs& args, bool save_frames, const Frame& frame, int index,
               const BoardDetector& detector, const CameraModel& camera, std::ostream& out,
               CaptureSummary* summary) {
  BoardDetection detection;
  const FrameFigures figures = CheckFrame(frame.image, detector, camera, &detection);
  ++summary->frames;
  if (figures.status != BoardDetection::Status::kNoBoard) ++summary->with_board;
  out << "frame " << index;
  if (!frame.origin.empty()) out << " (" << frame.origin << ")";
  out << ": " << FormatFrameFigures(figures) << "\n" << std::flush;
  const fs::path dir(args.out_dir);
  if (save_frames) WritePng(dir / Numbered("frame", index), frame.image);
  if (!args.draw) return;
  const cv::Mat overlay = DrawFrameFigures(frame.image, detection, figures);
  if (save_frames) {
    WritePng(dir / Numbered("overlay", index), overlay);
  } else {
    ReplacePng(dir / "preview.png", overlay);
  }
}

}  // namespace

int FirstFreeFrameNumber(const std::vector<std::string>& file_names) {
  int next = 0;
  for (const std::string& name : file_names) {
    for (const std::string_view prefix : {"frame_", "overlay_"}) {
      if (name.size() <= prefix.size() + 4 || name.rfind(prefix, 0) != 0 ||
          name.substr(name.size() - 4) != ".png") {
        continue;
      }
      const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - 4);
      if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) {
        continue;
      }
      next = std::max(next, std::stoi(digits) + 1);
    }
  }
  return next;
}

CaptureSummary RunCapture(const CaptureArgs& args, bool save_frames, std::ostream& out,
                          const std::atomic<bool>& stop) {
  const BoardSpec board = ReadBoardYaml(args.board_path);
  const CameraIntrinsics intrinsics = ReadCameraYaml(args.camera_path);
  const BoardDetector detector(board, intrinsics);
  if (!detector.ok()) throw std::runtime_error(args.board_path + ": " + detector.error());
  const CameraModel camera(intrinsics);
  if ((save_frames || args.draw) && args.out_dir.empty()) {
    throw std::invalid_argument(save_frames
                                    ? "--out-dir: the folder to save the frames in is required"
                                    : "--draw needs --out-dir (the folder of preview.png)");
  }
  if (!args.out_dir.empty()) fs::create_directories(args.out_dir);

  // Saved frames are numbered on from those already in the folder: a second capture (or a
  // loop of --count 1) adds to the set instead of overwriting it.
  const int first_number =
      save_frames ? FirstFreeFrameNumber(FileNamesIn(fs::path(args.out_dir))) : 0;
  SimSource* pose_sequence_sim = nullptr;
  std::unique_ptr<FrameSource> source =
      MakeCaptureSource(args, save_frames, board, intrinsics, &pose_sequence_sim);
  StartSource(*source);
  CaptureSummary summary;
  std::optional<std::chrono::steady_clock::time_point> last_taken;
  while ((args.count == 0 || summary.frames < args.count) && !stop.load()) {
    const int number = first_number + summary.frames;
    // The frame's number picks its pose: a loop of --count 1 varies the board as well.
    if (pose_sequence_sim) pose_sequence_sim->SetPose(SimCapturePose(board, intrinsics, number));
    std::optional<Frame> frame = source->Next(std::chrono::milliseconds(1000));
    if (!frame) {
      // The error first: an unreadable last file also leaves the file source finished, and
      // was skipped silently ("checked 1 frame(s)", exit 0) where any other was an error.
      if (!source->error().empty()) throw std::runtime_error(source->error());
      if (source->finished()) break;
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    if (last_taken && std::chrono::duration<double>(now - *last_taken).count() < args.interval_s) {
      continue;
    }
    last_taken = now;
    RequireTheCameraFilesSize(*frame, intrinsics, args.camera_path);
    TakeFrame(args, save_frames, *frame, number, detector, camera, out, &summary);
  }
  source->Stop();
  source->Close();
  out << (save_frames ? "captured " : "checked ") << summary.frames << " frame(s), "
      << summary.with_board << " showing the board";
  if (save_frames && summary.frames > 0) {
    out << ", in " << args.out_dir << " as " << Numbered("frame", first_number) << " to "
        << Numbered("frame", first_number + summary.frames - 1);
  }
  out << "\n";
  return summary;
}

namespace {

void AddCaptureOptions(CLI::App* command, CaptureArgs* args) {
  command->add_option("--source", args->source, "Frames: libcamera, sim or dir:PATH")
      ->capture_default_str();
  h4::cli::AddBoardOption(command, &args->board_path)->required();
  h4::cli::AddCameraOption(command, &args->camera_path,
                           "Camera intrinsics YAML (OpenCV); nominal values will do before the "
                           "camera is calibrated")
      ->required();
  command->add_flag("--draw", args->draw, "Also write the frame with its detection drawn");
  h4::cli::AddOptionShowingDefault(
      command, "--interval", &args->interval_s,
      "Live sources: at least this long between frames taken, s (time to move "
      "the board)",
      CLI::Range(0.0, 3600.0));
  command->add_option("--camera-id", args->camera_id, "libcamera camera id (default the first)");
  command
      ->add_option("--exposure-us", args->exposure_us,
                   "libcamera: fixed exposure time, us (default 0: automatic)")
      ->check(CLI::Range(0.0, 1e6));
  h4::cli::AddOptionShowingDefault(command, "--gain", &args->analogue_gain,
                                   "libcamera: analogue gain (fixed exposure)",
                                   CLI::Range(1.0, 64.0));
  command
      ->add_option("--sim-pose", args->sim_pose,
                   "sim: X_CT as x,y,z,qw,qx,qy,qz (m); default: capture shows the board at a "
                   "sequence of tilted poses over the whole image (frame N at pose N), "
                   "preview centred 0.5 m ahead")
      ->delimiter(',')
      ->expected(7);
  h4::cli::AddOptionShowingDefault(command, "--sim-preset", &args->sim_preset,
                                   "sim: clean or processed", h4::cli::OneOf(kRenderPresetNames));
  h4::cli::AddOptionShowingDefault(
      command, "--sim-exposure", &args->sim_exposure,
      "sim: scale of the light (1: the preset's; above ~1.2 the white clips)",
      CLI::Range(0.05, 20.0));
}

int CaptureExitCode(const CaptureSummary& summary, const std::atomic<bool>& stopped) {
  if (summary.frames == 0 && stopped.load()) return h4::cli::kExitInterrupted;
  if (summary.with_board > 0) return h4::cli::kExitSuccess;
  std::cerr << "h4cam: no frame showed the board\n";
  return h4::cli::kExitNothingUsable;
}

/// What `h4cam capture` and `h4cam preview` differ in; both take AddCaptureOptions and run
/// RunCapture. Saving frames is what needs a folder and at least one frame: preview keeps
/// no frame, and without --count checks frames until it is interrupted.
struct CaptureCommandText {
  bool save_frames;
  const char* count_help;
  const char* out_dir_help;
  const char* footer;
};

void DeclareCaptureOrPreviewCommand(CLI::App* command, const CaptureCommandText& text) {
  const auto args = std::make_shared<CaptureArgs>();
  args->count = text.save_frames ? CaptureArgs{}.count : 0;
  AddCaptureOptions(command, args.get());
  h4::cli::AddOptionShowingDefault(command, "--count", &args->count, text.count_help,
                                   CLI::Range(text.save_frames ? 1 : 0, 100000));
  CLI::Option* out_dir =
      h4::cli::AddOutDirOption(command, &args->out_dir, text.out_dir_help, "--out");
  if (text.save_frames) out_dir->required();
  command->footer(text.footer);
  h4::cli::RunWhenParsed(
      command, args, [save_frames = text.save_frames](const CaptureArgs& parsed) {
        // The capture loop polls the flag between frames.
        const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
        return CaptureExitCode(RunCapture(parsed, save_frames, std::cout, stop), stop);
      });
}

const CaptureCommandText kCaptureText = {
    .save_frames = true,
    .count_help = "Frames to save",
    .out_dir_help =
        "Folder of frame_NNNN.png (and overlay_NNNN.png), numbered on after the highest "
        "already there: never overwritten, so captures add to a set",
    .footer = "Exit codes: 0 some frame showed the board, 3 none did, 130 interrupted, 1 error."};

const CaptureCommandText kPreviewText = {
    .save_frames = false,
    .count_help = "Frames to check (0: until Ctrl-C)",
    .out_dir_help = "Folder of preview.png (with --draw)",
    .footer =
        "Exit codes: 0 some frame showed the board, 3 none did, 130 interrupted before any "
        "frame, 1 error."};

}  // namespace

void DeclareCaptureCommand(CLI::App* command) {
  DeclareCaptureOrPreviewCommand(command, kCaptureText);
}

void DeclarePreviewCommand(CLI::App* command) {
  DeclareCaptureOrPreviewCommand(command, kPreviewText);
}

}  // namespace h4::cam
