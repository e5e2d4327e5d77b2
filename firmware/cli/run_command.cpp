// `h4cam run`; see run_command.h.
#include "firmware/cli/run_command.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/stop_signal.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "firmware/service/camera_service.h"
#include "firmware/service/sd_notify.h"
#include "firmware/service/service_node.h"
#include "firmware/sources/frame_source_spec.h"
#include "firmware/sources/image_file_source.h"
#include "firmware/sources/libcamera_source.h"
#include "firmware/sources/sim_source.h"
#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"

namespace h4::cam {
namespace {

LibcameraSourceOptions LibcameraOptions(const ServiceConfig& config) {
  LibcameraSourceOptions o;
  o.camera_id = config.camera_id;
  o.width = config.width_px;
  o.height = config.height_px;
  o.rotate_180 = config.rotate_180;
  o.auto_exposure = config.exposure_time_us == 0;
  o.exposure_time = std::chrono::microseconds(static_cast<int64_t>(config.exposure_time_us));
  o.analogue_gain = static_cast<float>(config.analogue_gain);
  o.frame_rate_hz = 1e6 / config.frame_duration_us;
  return o;
}

// Fails before the service runs: the reason on stderr and in a STATE_ERROR status.
int Fail(bus::LcmBus* bus, const ServiceConfig& config, const std::string& why, std::ostream& err) {
  err << h4::cli::ErrorLine("h4cam", why) << "\n";
  if (bus != nullptr && bus->good()) {
    h4msgs::camera_status_t status{};
    status.utime = NowUtime();
    status.camera_id = config.MessageCameraId();
    status.state = h4msgs::camera_status_t::STATE_ERROR;
    status.exposure_us = config.exposure_time_us;
    status.analogue_gain = config.analogue_gain;
    status.last_error = why;
    bus->Publish(channels::kCameraStatus, status);
  }
  NotifyStatus("error: " + why);
  return 1;
}

// The renderer as a camera, in real time, showing the board where the sim robot puts it.
std::unique_ptr<SimSource> MakeRealTimeSimSource(const ServiceConfig& config,
                                                 const BoardSpec& board,
                                                 const CameraIntrinsics& rendered_camera) {
  SimSourceOptions sim_options;
  sim_options.render = config.sim_render;
  sim_options.frame_rate_hz = 1e6 / config.frame_duration_us;
  sim_options.start_utime = NowUtime();
  sim_options.real_time = true;
  return std::make_unique<SimSource>(board, rendered_camera, sim_options);
}

CameraServiceOptions ServiceOptionsOf(const ServiceConfig& config, const FrameSourceSpec& spec) {
  CameraServiceOptions options;
  options.camera_id = config.MessageCameraId();
  options.board_id = std::filesystem::path(config.board_path).stem().string();
  options.default_frames = config.frames_averaged;
  options.free_run_hz = config.free_run_hz;
  options.max_spread_px = config.max_spread_px;
  options.exposure_us = config.exposure_time_us;
  options.analogue_gain = config.analogue_gain;
  options.drain_when_idle = spec.kind == FrameSourceSpec::Kind::kLibcamera;
  return options;
}

}  // namespace

ServiceConfig ResolveRunConfig(const RunArgs& args) {
  ServiceConfig config;
  if (!args.config_path.empty()) config = ReadServiceConfig(args.config_path);
  if (args.source) config.source = *args.source;
  if (args.board_path) config.board_path = *args.board_path;
  if (args.camera_path) config.camera_intrinsics_path = *args.camera_path;
  if (args.lcm_url) config.lcm_url = *args.lcm_url;
  if (args.auth_key_path) config.auth_key_file = *args.auth_key_path;
  if (args.camera_id) config.camera_id = *args.camera_id;
  if (args.frames) config.frames_averaged = *args.frames;
  if (args.free_run_hz) config.free_run_hz = *args.free_run_hz;
  if (args.sim_camera_path) config.sim_camera_path = *args.sim_camera_path;
  if (args.sim_preset && !RenderPresetByName(*args.sim_preset, &config.sim_render)) {
    throw std::runtime_error("--sim-preset '" + *args.sim_preset +
                             "': expected clean or processed");
  }
  std::string why;
  if (!config.IsValid(&why)) throw std::runtime_error("run: " + why);
  return config;
}

int RunService(const ServiceConfig& config, std::ostream& err, const std::atomic<bool>& stop) {
  std::optional<bus::BusAuth> auth;
  try {
    auth = bus::BusAuthFromKeyFile(config.auth_key_file);
  } catch (const std::exception& e) {
    return Fail(nullptr, config, e.what(), err);
  }
  bus::LcmBus bus(config.lcm_url, bus::WireLimits{}, std::move(auth));
  if (!bus.good()) return Fail(nullptr, config, bus.error(), err);

  std::string why;
  const std::optional<FrameSourceSpec> spec = ParseFrameSourceSpec(config.source, &why);
  if (!spec) return Fail(&bus, config, why, err);
  std::unique_ptr<FrameSource> source;
  SimSource* sim = nullptr;
  if (spec->kind == FrameSourceSpec::Kind::kLibcamera) {
    // The camera first: on a machine without one, that is the error to report, whatever
    // the state of the board and intrinsics files.
    auto camera = std::make_unique<LibcameraSource>(LibcameraOptions(config));
    if (!camera->Open()) return Fail(&bus, config, camera->error(), err);
    camera->Close();
    source = std::move(camera);
  }
  if (config.board_path.empty()) return Fail(&bus, config, "no board file (--board)", err);
  if (config.camera_intrinsics_path.empty()) {
    return Fail(&bus, config, "no camera intrinsics file (--camera)", err);
  }
  BoardSpec board;
  CameraIntrinsics intrinsics;
  CameraIntrinsics rendered_camera;
  try {
    board = ReadBoardYaml(config.board_path);
    intrinsics = ReadCameraYaml(config.camera_intrinsics_path);
    rendered_camera =
        config.sim_camera_path.empty() ? intrinsics : ReadCameraYaml(config.sim_camera_path);
  } catch (const std::exception& e) {
    return Fail(&bus, config, e.what(), err);
  }
  if (spec->kind == FrameSourceSpec::Kind::kSim) {
    std::unique_ptr<SimSource> sim_source = MakeRealTimeSimSource(config, board, rendered_camera);
    sim = sim_source.get();
    source = std::move(sim_source);
  } else if (spec->kind == FrameSourceSpec::Kind::kImageFiles) {
    source = std::make_unique<ImageFileSource>(std::vector<std::string>{spec->path});
  }

  const CameraServiceOptions options = ServiceOptionsOf(config, *spec);
  CameraService service(options, *source, board, intrinsics);
  if (!service.Start()) return Fail(&bus, config, service.last_error(), err);

  // The sim source renders the board where H4_SIM_BOARD_TRUTH puts it.
  ServiceNode::ShowTruth show_truth;
  if (sim != nullptr) show_truth = [sim](const RigidTransform& X_CT) { sim->SetPose(X_CT); };
  ServiceNode node(bus, service, show_truth,
                   std::chrono::duration<double>(config.heartbeat_period_s));
  NotifyReady();
  NotifyStatus("running: " + source->Describe() + " on " + bus.url());
  err << "h4cam run: " << source->Describe() << ", board " << options.board_id << ", LCM "
      << bus.url()
      << (config.auth_key_file.empty() ? "" : ", authenticated with " + config.auth_key_file)
      << "\n";
  while (!stop.load()) node.Poll(std::chrono::milliseconds(100));

  NotifyStopping();
  service.Stop();
  node.PublishStatus();  // STATE_STOPPING
  err << "h4cam run: stopped after " << service.measurements_total() << " measurement(s)\n";
  return 0;
}

void DeclareRunCommand(CLI::App* command) {
  const auto args = std::make_shared<RunArgs>();
  command->add_option("--config", args->config_path, "Service configuration YAML")
      ->check(CLI::ExistingFile);
  command->add_option("--source", args->source, "Frames: libcamera (default), sim or dir:PATH");
  h4::cli::AddBoardOption(command, &args->board_path);
  h4::cli::AddCameraOption(command, &args->camera_path);
  h4::cli::AddFramesOption(command, &args->frames, "Frames averaged per measurement (default 10)")
      ->check(CLI::Range(1, kMaxFramesPerRequest));
  command->add_option("--free-run", args->free_run_hz, "Measure continuously at this rate, Hz")
      ->check(CLI::Range(0.0, 100.0));
  command->add_option("--sim-preset", args->sim_preset,
                      "Rendered frames of --source sim: processed (default: a camera module's "
                      "sRGB output with defocus, gradient, shot noise) or clean");
  command
      ->add_option("--sim-camera", args->sim_camera_path,
                   "Camera YAML --source sim renders through (the true camera; default: "
                   "--camera). With a --camera that differs from it, the measurement "
                   "assumes a wrong camera file, as a real intrinsic calibration does")
      ->check(CLI::ExistingFile);
  h4::cli::AddLcmUrlOption(command, &args->lcm_url);
  h4::cli::AddAuthKeyOption(command, &args->auth_key_path, "lcm.auth_key_file, else off");
  command->add_option(
      "--camera-id", args->camera_id,
      "libcamera camera id (also the name in the messages unless camera.name is set)");
  h4::cli::RunWhenParsed(command, args, [](const RunArgs& parsed) {
    // The service's loop polls the flag at least every 100 ms.
    const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
    return RunService(ResolveRunConfig(parsed), std::cerr, stop);
  });
}

}  // namespace h4::cam
