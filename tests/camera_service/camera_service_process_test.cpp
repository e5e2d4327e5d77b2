// `h4cam run --source sim` as a separate process over real udpm multicast, inside a private
// network namespace (scripts/in-private-netns, loopback only) so that nothing reaches or
// comes from the machine's network: truth and request in, board pose and heartbeats out,
// SIGTERM -> final STATE_STOPPING status and exit code 0; without a camera, a STATE_ERROR
// status and a non-zero exit. Skipped where no network namespace can be made.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/service/service_node.h"
#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"
#include "tests/support/private_netns.h"
#include "tests/support/program_command.h"

extern char** environ;

namespace h4::cam {
namespace {

constexpr const char* kUrl = "udpm://239.255.76.67:7667?ttl=0";

// Starts `command` (program, arguments) as a child process, through the emulator in a cross
// build (program_command.h).
bool Spawn(const std::vector<std::string>& command, pid_t* pid) {
  std::vector<std::string> args = test::ProgramArgv(command);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return posix_spawn(pid, args[0].c_str(), nullptr, nullptr, argv.data(), environ) == 0;
}

// The spawned service, killed and reaped when the test leaves by any path (a failed
// assertion must not leave it running: it would outlive the test and hold its output).
class SpawnedProcess {
 public:
  SpawnedProcess() = default;
  SpawnedProcess(const SpawnedProcess&) = delete;
  SpawnedProcess& operator=(const SpawnedProcess&) = delete;
  ~SpawnedProcess() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  pid_t* pid() { return &pid_; }
  /// Waits for the exit; the process is then no longer ours to kill.
  bool Wait(int* status) {
    const bool reaped = waitpid(pid_, status, 0) == pid_;
    pid_ = 0;
    return reaped;
  }

 private:
  pid_t pid_ = 0;
};

// Runs inside the namespace (started by the test below through scripts/in-private-netns).
TEST(CameraServiceProcessTest, ChildInNamespace) {
  if (!test::InPrivateNamespace()) GTEST_SKIP() << "only inside scripts/in-private-netns";
  const std::string binary = H4_BINARY_DIR "/firmware/h4cam";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("h4cam_run_{}", getpid());
  std::filesystem::create_directories(dir);
  const std::string board = (dir / "paper_board.yaml").string();
  const std::string camera = (dir / "camera.yaml").string();
  WriteBoardYaml(board, scenes::PaperBoard());
  WriteCameraYaml(camera, scenes::PaperCamera());

  bus::LcmBus bus(kUrl);
  ASSERT_TRUE(bus.good()) << bus.error();
  std::vector<h4msgs::board_pose_t> poses;
  std::vector<h4msgs::camera_status_t> statuses;
  bus.Subscribe<h4msgs::board_pose_t>(channels::kBoardPose,
                                      [&](const h4msgs::board_pose_t& m) { poses.push_back(m); });
  bus.Subscribe<h4msgs::camera_status_t>(
      channels::kCameraStatus, [&](const h4msgs::camera_status_t& m) { statuses.push_back(m); });

  SpawnedProcess service;
  // The processed preset, as a camera module delivers its frames (sRGB-like response,
  // defocus, gradient, shot noise), with the depth tolerance below.
  ASSERT_TRUE(Spawn({binary, "run", "--source", "sim", "--sim-preset", "processed", "--board",
                     board, "--camera", camera, "--lcm-url", kUrl, "--camera-id", "proc-cam"},
                    service.pid()));

  // Wait for the first heartbeat: the service is up and subscribed.
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(20 * test::kEmulationTimeScale);
  while (statuses.empty() && std::chrono::steady_clock::now() < deadline) {
    bus.Handle(std::chrono::milliseconds(100));
  }
  ASSERT_FALSE(statuses.empty()) << "no heartbeat from h4cam run";
  EXPECT_EQ(statuses[0].camera_id, "proc-cam");

  const RigidTransform X_CT = scenes::RandomPoses(1, 77)[0];
  h4msgs::sim_board_truth_t truth{};
  const Eigen::Vector4d q = X_CT.quaternion_wxyz();
  for (int i = 0; i < 3; ++i) truth.translation[i] = X_CT.translation()[i];
  for (int i = 0; i < 4; ++i) truth.quaternion[i] = q[i];
  bus.Publish(channels::kSimBoardTruth, truth);
  h4msgs::capture_request_t request{};
  request.pose_id = 1234;
  bus.Publish(channels::kCaptureRequest, request);
  while (poses.empty() && std::chrono::steady_clock::now() < deadline) {
    bus.Handle(std::chrono::milliseconds(100));
  }
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].pose_id, 1234);
  EXPECT_EQ(poses[0].status, int8_t{h4msgs::board_pose_t::STATUS_OK});
  EXPECT_LT(std::abs(poses[0].translation[2] - X_CT.translation().z()), 0.1e-3);

  kill(*service.pid(), SIGTERM);
  int status = 0;
  ASSERT_TRUE(service.Wait(&status));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  bus.Handle(std::chrono::milliseconds(200));
  EXPECT_EQ(statuses.back().state, int8_t{h4msgs::camera_status_t::STATE_STOPPING});
  EXPECT_EQ(statuses.back().measurements_total, 1);
  std::filesystem::remove_all(dir);

  // The default libcamera source on this machine (no camera): a STATE_ERROR status naming
  // the cause goes out before the non-zero exit.
  statuses.clear();
  SpawnedProcess without_camera;
  ASSERT_TRUE(Spawn({binary, "run", "--lcm-url", kUrl}, without_camera.pid()));
  ASSERT_TRUE(without_camera.Wait(&status));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0);
  bus.Handle(std::chrono::milliseconds(200));
  ASSERT_EQ(statuses.size(), 1u);
  EXPECT_EQ(statuses[0].state, int8_t{h4msgs::camera_status_t::STATE_ERROR});
  EXPECT_NE(statuses[0].last_error.find("no camera"), std::string::npos) << statuses[0].last_error;
}

TEST(CameraServiceProcessTest, RunAnswersACaptureRequestOverUdpmAndStopsOnSigterm) {
  const std::string binary = H4_BINARY_DIR "/firmware/h4cam";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  test::RunChildTestInPrivateNamespace("CameraServiceProcessTest.ChildInNamespace",
                                       60 * test::kEmulationTimeScale);
}

}  // namespace
}  // namespace h4::cam
