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
#include "firmware/sources/libcamera_source.h"
#include "firmware/sources/make_frame_source.h"
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

// The renderer as a camera, in real time.
SimSourceOptions RealTimeSimOptions(const ServiceConfig& config) {
  SimSourceOptions sim_options;
  sim_options.render = config.sim_render;
  sim_options.frame_rate_hz = 1e6 / config.frame_duration_us;
  sim_options.start_utime = NowUtime();
  sim_options.real_time = true;
  return sim_options;
}

// The files the service reads: the board, the intrinsics the measurement assumes and the
// camera `--source sim` renders through.
struct ServiceFiles {
  BoardSpec board;
  CameraIntrinsics intrinsics;
  CameraIntrinsics rendered_camera;
};

// The files `config` names; "" when they were read, else the reason.
std::string ReadServiceFiles(const ServiceConfig& config, ServiceFiles* files) {
  if (config.board_path.empty()) return "no board file (--board)";
  if (config.camera_intrinsics_path.empty()) return "no camera intrinsics file (--camera)";
  try {
    files->board = ReadBoardYaml(config.board_path);
    files->intrinsics = ReadCameraYaml(config.camera_intrinsics_path);
    files->rendered_camera =
        config.sim_camera_path.empty() ? files->intrinsics : ReadCameraYaml(config.sim_camera_path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
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

void RunFlags::ApplyTo(ServiceConfig* config) const {
  for (const Binding& binding : bindings_) {
    if (binding.option->count() > 0) binding.apply(config);
  }
}

CLI::Option* RunFlags::WhenGiven(CLI::Option* option, std::function<void(ServiceConfig*)> apply) {
  bindings_.push_back({option, std::move(apply)});
  return option;
}

ServiceConfig ResolveRunConfig(const RunFlags& flags) {
  ServiceConfig config;
  if (!flags.config_path.empty()) config = ReadServiceConfig(flags.config_path);
  flags.ApplyTo(&config);
  std::string why;
  if (!config.IsValid(&why)) throw std::invalid_argument("run: " + why);
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
  FrameSourceParts parts;
  parts.libcamera = LibcameraOptions(config);
  std::unique_ptr<FrameSource> source;
  if (spec->kind == FrameSourceSpec::Kind::kLibcamera) {
    // The camera first: on a machine without one, that is the error to report, whatever
    // the state of the board and intrinsics files.
    source = MakeFrameSource(*spec, parts);
    if (!source->Open()) return Fail(&bus, config, source->error(), err);
    source->Close();
  }
  ServiceFiles files;
  why = ReadServiceFiles(config, &files);
  if (!why.empty()) return Fail(&bus, config, why, err);
  if (source == nullptr) {
    parts.board = &files.board;
    parts.rendered_camera = &files.rendered_camera;
    parts.sim = RealTimeSimOptions(config);
    source = MakeFrameSource(*spec, parts);
  }
  SimSource* sim =
      spec->kind == FrameSourceSpec::Kind::kSim ? static_cast<SimSource*>(source.get()) : nullptr;

  const CameraServiceOptions options = ServiceOptionsOf(config, *spec);
  CameraService service(options, *source, files.board, files.intrinsics);
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

namespace {

// A flag with no shared declaration (common/cli/shared_options.h) that sets `field`.
template <typename T>
CLI::Option* BindOption(CLI::App* command, RunFlags* flags, const std::string& name,
                        T ServiceConfig::*field, const std::string& help) {
  return flags->Bind(field, [&](T* value) { return command->add_option(name, *value, help); });
}

// --sim-preset names a whole image formation (render_options.h), not one field: it
// replaces the file's sim: block.
void DeclareSimPresetOption(CLI::App* command, RunFlags* flags) {
  const auto name = std::make_shared<std::string>();
  CLI::Option* option =
      command->add_option("--sim-preset", *name,
                          "Rendered frames of --source sim: processed (default: a camera module's "
                          "sRGB output with defocus, gradient, shot noise) or clean");
  flags->WhenGiven(option, [name](ServiceConfig* config) {
    if (!RenderPresetByName(*name, &config->sim_render)) {
      throw std::invalid_argument("--sim-preset '" + *name + "': expected clean or processed");
    }
  });
}

}  // namespace

void DeclareRunOptions(CLI::App* command, RunFlags* flags) {
  command->add_option("--config", flags->config_path, "Service configuration YAML")
      ->check(CLI::ExistingFile);
  BindOption(command, flags, "--source", &ServiceConfig::source,
             "Frames: libcamera (default), sim or dir:PATH");
  flags->Bind(&ServiceConfig::board_path,
              [command](std::string* path) { return h4::cli::AddBoardOption(command, path); });
  flags->Bind(&ServiceConfig::camera_intrinsics_path,
              [command](std::string* path) { return h4::cli::AddCameraOption(command, path); });
  flags->Bind(&ServiceConfig::frames_averaged, [command](int* frames) {
    return h4::cli::AddFramesOption(command, frames, "Frames averaged per measurement (default 10)")
        ->check(CLI::Range(1, kMaxFramesPerRequest));
  });
  BindOption(command, flags, "--free-run", &ServiceConfig::free_run_hz,
             "Measure continuously at this rate, Hz")
      ->check(CLI::Range(0.0, 100.0));
  DeclareSimPresetOption(command, flags);
  BindOption(command, flags, "--sim-camera", &ServiceConfig::sim_camera_path,
             "Camera YAML --source sim renders through (the true camera; default: "
             "--camera). With a --camera that differs from it, the measurement "
             "assumes a wrong camera file, as a real intrinsic calibration does")
      ->check(CLI::ExistingFile);
  flags->Bind(&ServiceConfig::lcm_url,
              [command](std::string* url) { return h4::cli::AddLcmUrlOption(command, url); });
  flags->Bind(&ServiceConfig::auth_key_file, [command](std::string* path) {
    return h4::cli::AddAuthKeyOption(command, path, "lcm.auth_key_file, else off");
  });
  BindOption(command, flags, "--camera-id", &ServiceConfig::camera_id,
             "libcamera camera id (also the name in the messages unless camera.name is set)");
}

void DeclareRunCommand(CLI::App* command) {
  const auto flags = std::make_shared<RunFlags>();
  DeclareRunOptions(command, flags.get());
  h4::cli::RunWhenParsed(command, flags, [](const RunFlags& parsed) {
    // The service's loop polls the flag at least every 100 ms.
    const std::atomic<bool>& stop = h4::cli::InstallStopSignalHandlers();
    return RunService(ResolveRunConfig(parsed), std::cerr, stop);
  });
}

}  // namespace h4::cam
