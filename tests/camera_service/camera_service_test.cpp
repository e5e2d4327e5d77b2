// The camera service over real LCM traffic (the in-process memq:// provider): capture
// requests answered with board poses measured on synthetic frames at the published true
// pose, bad messages counted and ignored, heartbeats, and `h4cam run` on a machine
// without a camera (the real binary).
#include "firmware/service/camera_service.h"

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/service/service_node.h"
#include "firmware/sources/image_file_source.h"
#include "firmware/sources/sim_source.h"
#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"
#include "tests/messages/wire_bytes.h"
#include "tests/support/program_command.h"

namespace h4::cam {
namespace {

h4msgs::sim_board_truth_t Truth(const RigidTransform& X_CT) {
  h4msgs::sim_board_truth_t truth{};
  truth.utime = NowUtime();
  truth.pose_id = 7;
  const Eigen::Vector4d q = X_CT.quaternion_wxyz();
  for (int i = 0; i < 3; ++i) truth.translation[i] = X_CT.translation()[i];
  for (int i = 0; i < 4; ++i) truth.quaternion[i] = q[i];
  truth.settled = true;
  return truth;
}

h4msgs::capture_request_t Request(int64_t pose_id, int32_t frame_count) {
  h4msgs::capture_request_t request{};
  request.utime = NowUtime();
  request.pose_id = pose_id;
  request.frame_count = frame_count;
  return request;
}

constexpr int64_t kStartUtime = 1'700'000'000'000'000;

// One service on a memq bus, as `h4cam run --source sim` wires it, plus a listener.
class ServiceFixture : public ::testing::Test {
 protected:
  explicit ServiceFixture(double free_run_hz = 0, std::optional<bus::BusAuth> auth = std::nullopt)
      : bus_("memq://", bus::WireLimits{}, std::move(auth)),
        sim_(scenes::PaperBoard(), scenes::PaperCamera(), SimOptions()),
        service_(Options(free_run_hz), sim_, scenes::PaperBoard(), scenes::PaperCamera()),
        node_(
            bus_, service_, [this](const RigidTransform& X_CT) { sim_.SetPose(X_CT); },
            std::chrono::seconds(1)) {
    bus_.Subscribe<h4msgs::board_pose_t>(
        channels::kBoardPose, [this](const h4msgs::board_pose_t& m) { poses_.push_back(m); });
    bus_.Subscribe<h4msgs::camera_status_t>(
        channels::kCameraStatus,
        [this](const h4msgs::camera_status_t& m) { statuses_.push_back(m); });
    bus_.Subscribe<h4msgs::board_corners_t>(channels::kBoardCorners,
                                            [this](const h4msgs::board_corners_t& m) {
                                              corners_.push_back(m);
                                              poses_before_corners_.push_back(poses_.size());
                                            });
  }
  // As `h4cam run --source sim`: synthetic timestamps start now.
  static SimSourceOptions SimOptions() {
    SimSourceOptions options;
    options.start_utime = kStartUtime;
    return options;
  }
  static CameraServiceOptions Options(double free_run_hz) {
    CameraServiceOptions options;
    options.camera_id = "test-cam";
    options.board_id = "paper";
    options.free_run_hz = free_run_hz;
    options.exposure_us = 5000;
    options.analogue_gain = 2;
    return options;
  }
  void SetUp() override {
    ASSERT_TRUE(bus_.good()) << bus_.error();
    ASSERT_TRUE(service_.Start()) << service_.last_error();
  }
  // Polls until `count` board poses arrived (or a generous number of iterations).
  void PollForPoses(size_t count) {
    for (int i = 0; i < 500 && poses_.size() < count; ++i) {
      node_.Poll(std::chrono::milliseconds(1));
      bus_.Handle(std::chrono::milliseconds(0));
    }
  }

  bus::LcmBus bus_;
  SimSource sim_;
  CameraService service_;
  ServiceNode node_;
  std::vector<h4msgs::board_pose_t> poses_;
  std::vector<h4msgs::camera_status_t> statuses_;
  std::vector<h4msgs::board_corners_t> corners_;
  std::vector<size_t> poses_before_corners_;  // poses received when each corners message came
};

TEST_F(ServiceFixture, CaptureRequestMeasuresTheTruePoseWithTheRequestsPoseId) {
  const RigidTransform X_CT = scenes::RandomPoses(1, 31)[0];
  bus_.Publish(channels::kSimBoardTruth, Truth(X_CT));
  bus_.Publish(channels::kCaptureRequest, Request(42, 0));
  PollForPoses(1);
  ASSERT_EQ(poses_.size(), 1u);
  const h4msgs::board_pose_t& m = poses_[0];
  EXPECT_EQ(m.pose_id, 42);
  ASSERT_EQ(m.status, int8_t{h4msgs::board_pose_t::STATUS_OK});
  EXPECT_EQ(m.frames_averaged, 10);
  EXPECT_EQ(m.corners_used, 144);
  EXPECT_EQ(m.camera_id, "test-cam");
  EXPECT_EQ(m.board_id, "paper");
  EXPECT_EQ(m.utime, kStartUtime);  // the first frame the service pulled
  const RigidTransform measured = RigidTransform::FromTranslationQuaternion(
      Eigen::Vector3d(m.translation[0], m.translation[1], m.translation[2]),
      Eigen::Vector4d(m.quaternion[0], m.quaternion[1], m.quaternion[2], m.quaternion[3]));
  EXPECT_LT((measured.translation() - X_CT.translation()).norm(), 0.1e-3);
  const double angle = So3Log(X_CT.rotation().transpose() * measured.rotation()).norm();
  EXPECT_LT(angle, RadiansFromDegrees(0.02));
  // Covariance: symmetric, positive variances, order (t in C, r in T).
  for (int i = 0; i < 6; ++i) {
    EXPECT_GT(m.covariance[7 * i], 0.0);
    for (int j = 0; j < 6; ++j) EXPECT_DOUBLE_EQ(m.covariance[6 * i + j], m.covariance[6 * j + i]);
  }
  EXPECT_GT(m.reprojection_rms_px, 0.0);
  EXPECT_LT(m.reprojection_rms_px, 0.5);
}

// The corners travel right after their pose, same pose_id and utime, on the board's ids,
// where the true pose projects them (messages/README.md, H4_BOARD_CORNERS).
TEST_F(ServiceFixture, AnOkPoseIsFollowedByItsCorners) {
  const RigidTransform X_CT = scenes::RandomPoses(1, 31)[0];
  bus_.Publish(channels::kSimBoardTruth, Truth(X_CT));
  bus_.Publish(channels::kCaptureRequest, Request(42, 0));
  PollForPoses(1);
  bus_.Handle(std::chrono::milliseconds(0));
  ASSERT_EQ(poses_.size(), 1u);
  ASSERT_EQ(corners_.size(), 1u);
  EXPECT_EQ(poses_before_corners_[0], 1u);
  EXPECT_EQ(node_.board_corners_published(), 1);
  const h4msgs::board_corners_t& c = corners_[0];
  EXPECT_EQ(c.pose_id, 42);
  EXPECT_EQ(c.utime, poses_[0].utime);
  EXPECT_EQ(c.camera_id, "test-cam");
  ASSERT_EQ(c.corner_count, poses_[0].corners_used);
  const AprilGridSpec board = scenes::PaperBoard();
  const BoardModel model(board);
  const CameraModel camera(scenes::PaperCamera());
  for (size_t i = 0; i < static_cast<size_t>(c.corner_count); ++i) {
    EXPECT_EQ(c.tag_id[i], board.first_id + c.corner[i] / 4);
    EXPECT_GT(c.sigma_px[i], 0.0);
    const std::optional<Eigen::Vector3d> p_TQ = model.Corner(c.corner[i]);
    ASSERT_TRUE(p_TQ.has_value());
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(X_CT * *p_TQ, &uv));
    EXPECT_LT((uv - Eigen::Vector2d(c.u[i], c.v[i])).norm(), 0.3) << c.corner[i];
  }
}

TEST_F(ServiceFixture, WithoutABoardTheAnswerIsNoBoard) {
  bus_.Publish(channels::kCaptureRequest, Request(3, 2));
  PollForPoses(1);
  ASSERT_EQ(poses_.size(), 1u);
  EXPECT_EQ(poses_[0].pose_id, 3);
  EXPECT_EQ(poses_[0].status, int8_t{h4msgs::board_pose_t::STATUS_NO_BOARD});
  EXPECT_EQ(poses_[0].frames_averaged, 2);
  EXPECT_EQ(poses_[0].translation[2], 0.0);
  EXPECT_TRUE(corners_.empty()) << "no pose, no corners";
}

TEST_F(ServiceFixture, MalformedAndImpossibleMessagesAreCountedAndIgnored) {
  const std::array<uint8_t, 5> garbage = {1, 2, 3, 4, 5};
  bus_.lcm().publish(channels::kCaptureRequest, garbage.data(), garbage.size());
  bus_.Publish(channels::kCaptureRequest, Request(-1, 0));    // pose_id < 0
  bus_.Publish(channels::kCaptureRequest, Request(5, -2));    // frame_count < 0
  bus_.Publish(channels::kCaptureRequest, Request(6, 1001));  // frame_count > 1000
  h4msgs::sim_board_truth_t bad = Truth(scenes::RandomPoses(1, 5)[0]);
  bad.quaternion[0] = 3;  // not a unit quaternion
  bus_.Publish(channels::kSimBoardTruth, bad);
  for (int i = 0; i < 20; ++i) node_.Poll(std::chrono::milliseconds(1));
  bus_.Handle(std::chrono::milliseconds(0));
  EXPECT_EQ(bus_.decode_failures(), 1);
  EXPECT_EQ(service_.rejected_requests(), 3);
  EXPECT_EQ(node_.invalid_truths(), 1);
  EXPECT_FALSE(sim_.pose().has_value());
  EXPECT_TRUE(poses_.empty());
  // Still serving afterwards.
  bus_.Publish(channels::kCaptureRequest, Request(8, 1));
  PollForPoses(1);
  ASSERT_EQ(poses_.size(), 1u);
  EXPECT_EQ(poses_[0].pose_id, 8);
}

bus::AuthKey TestKey(uint8_t fill) {
  return bus::AuthKey{std::vector<uint8_t>(32, fill), "test key"};
}

// The service with authentication on (h4cam run --auth-key): the fixture's own publications
// are the campaign's, signed with the key.
class AuthenticatedServiceFixture : public ServiceFixture {
 protected:
  AuthenticatedServiceFixture() : ServiceFixture(0, bus::BusAuth{TestKey(1), {}}) {}

  void PublishRaw(const std::vector<uint8_t>& bytes) {
    bus_.lcm().publish(channels::kCaptureRequest, bytes.data(),
                       static_cast<unsigned>(bytes.size()));
  }
  static std::vector<uint8_t> Sealed(bus::MessageAuthenticator& sender,
                                     const h4msgs::capture_request_t& request) {
    const std::vector<uint8_t> bytes = bus::wire_bytes::Encode(request);
    return sender.Seal(channels::kCaptureRequest, bytes.data(), bytes.size(), NowUtime());
  }
};

TEST_F(AuthenticatedServiceFixture, IgnoresCaptureRequestsWithoutTheKeyAndAnswersTheRest) {
  PublishRaw(bus::wire_bytes::Encode(Request(61, 1)));  // an attacker without the key
  bus::MessageAuthenticator attacker(TestKey(9), {});
  PublishRaw(Sealed(attacker, Request(62, 1)));  // signed with another key
  bus::MessageAuthenticator campaign(TestKey(1), {});
  const std::vector<uint8_t> genuine = Sealed(campaign, Request(63, 1));
  PublishRaw(genuine);
  PublishRaw(genuine);  // replayed
  bus_.Publish(channels::kCaptureRequest, Request(64, 1));
  PollForPoses(3);
  std::vector<int64_t> answered;
  for (const auto& pose : poses_) answered.push_back(pose.pose_id);
  EXPECT_EQ(answered, (std::vector<int64_t>{63, 64}));
  EXPECT_EQ(bus_.auth_failures(channels::kCaptureRequest), 3);
  EXPECT_EQ(bus_.auth_failures(bus::AuthVerdict::kUnauthenticated), 1);
  EXPECT_EQ(bus_.auth_failures(bus::AuthVerdict::kForeignKey), 1);
  EXPECT_EQ(bus_.auth_failures(bus::AuthVerdict::kReplayed), 1);
  EXPECT_EQ(service_.rejected_requests(), 0) << "dropped by the bus, never seen by the service";
  EXPECT_GE(statuses_.size(), 1u) << "its own signed heartbeat reads back";
}

TEST_F(ServiceFixture, RequestsArrivingWhileBusyAreAnsweredInOrder) {
  bus_.Publish(channels::kCaptureRequest, Request(10, 3));
  bus_.Publish(channels::kCaptureRequest, Request(11, 4));
  bus_.Publish(channels::kCaptureRequest, Request(12, 0));
  PollForPoses(3);
  ASSERT_EQ(poses_.size(), 3u);
  EXPECT_EQ(poses_[0].pose_id, 10);
  EXPECT_EQ(poses_[0].frames_averaged, 3);
  EXPECT_EQ(poses_[1].pose_id, 11);
  EXPECT_EQ(poses_[1].frames_averaged, 4);
  EXPECT_EQ(poses_[2].pose_id, 12);
  EXPECT_EQ(poses_[2].frames_averaged, 10);
}

TEST_F(ServiceFixture, HeartbeatReportsStateCountsAndStopping) {
  node_.Poll(std::chrono::milliseconds(0));
  bus_.Handle(std::chrono::milliseconds(0));
  ASSERT_EQ(statuses_.size(), 1u);  // the first poll sends a heartbeat at once
  EXPECT_EQ(statuses_[0].state, int8_t{h4msgs::camera_status_t::STATE_IDLE});
  EXPECT_EQ(statuses_[0].camera_id, "test-cam");
  EXPECT_EQ(statuses_[0].exposure_us, 5000);
  EXPECT_EQ(statuses_[0].analogue_gain, 2);
  bus_.Publish(channels::kCaptureRequest, Request(1, 4));
  PollForPoses(1);
  service_.Stop();
  node_.PublishStatus();
  bus_.Handle(std::chrono::milliseconds(0));
  ASSERT_GE(statuses_.size(), 2u);
  const h4msgs::camera_status_t& last = statuses_.back();
  EXPECT_EQ(last.state, int8_t{h4msgs::camera_status_t::STATE_STOPPING});
  EXPECT_EQ(last.frames_total, 4);
  EXPECT_EQ(last.measurements_total, 1);
  EXPECT_GT(last.frame_rate_hz, 0.0);  // 4 frames within the last second
  EXPECT_TRUE(last.last_error.empty());
}

class FreeRunFixture : public ServiceFixture {
 protected:
  FreeRunFixture() : ServiceFixture(50.0) {}
};

TEST_F(FreeRunFixture, FreeRunningMeasurementsCarryPoseIdMinusOne) {
  bus_.Publish(channels::kSimBoardTruth, Truth(scenes::RandomPoses(1, 9)[0]));
  PollForPoses(2);
  ASSERT_EQ(poses_.size(), 2u);
  for (const auto& m : poses_) {
    EXPECT_EQ(m.pose_id, -1);
    EXPECT_EQ(m.status, int8_t{h4msgs::board_pose_t::STATUS_OK});
  }
}

TEST(CameraServiceTest, AnExhaustedFileSourceAnswersWithACameraError) {
  // A source that has no frames at all: the request ends with STATUS_CAMERA_ERROR.
  class EmptySource final : public DevicelessFrameSource {
   public:
    bool Open() override { return true; }
    std::optional<Frame> Next(std::chrono::milliseconds) override { return std::nullopt; }
    std::string Describe() const override { return "empty"; }
    bool finished() const override { return true; }
  } source;
  CameraService service(CameraServiceOptions{}, source, scenes::PaperBoard(),
                        scenes::PaperCamera());
  ASSERT_TRUE(service.Start());
  ASSERT_TRUE(service.SubmitRequest(Request(4, 0)));
  std::optional<h4msgs::board_pose_t> m;
  for (int i = 0; i < 3 && !m; ++i) m = service.Step();
  ASSERT_TRUE(m.has_value());
  EXPECT_EQ(m->pose_id, 4);
  EXPECT_EQ(m->status, int8_t{h4msgs::board_pose_t::STATUS_CAMERA_ERROR});
  EXPECT_NE(service.last_error().find("no more frames"), std::string::npos);
}

// issue 27 point 9: a checkerboard of 2 inner corners per side made OpenCV's chessboard
// detector throw, and `h4cam run` exited on its first capture request. The board reader now
// refuses such a board; the service answers any measurement that throws with a camera error
// and serves the next request.
TEST(CameraServiceTest, AMeasurementThatThrowsIsACameraErrorAndTheServiceGoesOn) {
  SimSource sim(scenes::PaperBoard(), scenes::PaperCamera(), SimSourceOptions{});
  CheckerboardSpec too_small;
  too_small.cols = 2;
  too_small.rows = 2;
  CameraService service(CameraServiceOptions{}, sim, BoardSpec{too_small}, scenes::PaperCamera());
  ASSERT_TRUE(service.Start()) << service.last_error();
  ASSERT_TRUE(service.SubmitRequest(Request(1, 1)));
  ASSERT_TRUE(service.SubmitRequest(Request(2, 1)));
  std::vector<h4msgs::board_pose_t> poses;
  for (int i = 0; i < 20 && poses.size() < 2; ++i) {
    std::optional<h4msgs::board_pose_t> m;
    ASSERT_NO_THROW(m = service.Step());
    if (m) poses.push_back(*m);
  }
  ASSERT_EQ(poses.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(poses[k].pose_id, static_cast<int64_t>(k + 1));
    EXPECT_EQ(poses[k].status, int8_t{h4msgs::board_pose_t::STATUS_CAMERA_ERROR});
  }
  EXPECT_NE(service.last_error().find("measurement failed"), std::string::npos)
      << service.last_error();
}

TEST(CameraServiceTest, DirectorySourceMeasuresImagesInNameOrderThenReportsExhaustion) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("h4cam_dir_source_{}", getpid());
  std::filesystem::create_directories(dir);
  SimSource sim(scenes::PaperBoard(), scenes::PaperCamera(), SimSourceOptions{});
  ASSERT_TRUE(sim.Open());
  sim.SetPose(scenes::RandomPoses(1, 3)[0]);
  for (int k = 0; k < 3; ++k) {
    cv::imwrite((dir / fmt::format("frame_{}.png", k)).string(),
                sim.Next(std::chrono::milliseconds(0))->image);
  }
  ImageFileSource source({dir.string()});
  CameraService service(CameraServiceOptions{}, source, scenes::PaperBoard(),
                        scenes::PaperCamera());
  ASSERT_TRUE(service.Start()) << service.last_error();
  ASSERT_TRUE(service.SubmitRequest(Request(1, 3)));
  ASSERT_TRUE(service.SubmitRequest(Request(2, 3)));
  std::vector<h4msgs::board_pose_t> poses;
  for (int i = 0; i < 20 && poses.size() < 2; ++i) {
    if (auto m = service.Step()) poses.push_back(*m);
  }
  std::filesystem::remove_all(dir);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].pose_id, 1);
  EXPECT_EQ(poses[0].status, int8_t{h4msgs::board_pose_t::STATUS_OK});
  EXPECT_EQ(poses[0].frames_averaged, 3);
  EXPECT_EQ(poses[1].pose_id, 2);
  EXPECT_EQ(poses[1].status, int8_t{h4msgs::board_pose_t::STATUS_CAMERA_ERROR});
}

TEST(CameraServiceTest, RunWithoutACameraExitsNonZeroWithAClearMessage) {
  const std::string binary = H4_BINARY_DIR "/firmware/h4cam";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  // memq: no multicast needed; the camera is what must be missing.
  FILE* pipe = popen(
      ("timeout 30 " + test::ProgramCommand(binary) + " run --lcm-url memq:// 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_NE(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(WEXITSTATUS(status), 124) << "timed out: " << output;
  EXPECT_NE(output.find("no camera"), std::string::npos) << output;
  EXPECT_NE(output.find("h4cam: error:"), std::string::npos) << output;
}

TEST(CameraServiceTest, RunRefusesAKeyFileOthersCanReadNamingIt) {
  const std::string binary = H4_BINARY_DIR "/firmware/h4cam";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  const std::string key =
      (std::filesystem::temp_directory_path() / fmt::format("h4cam_key_{}", getpid())).string();
  { std::ofstream(key) << std::string(32, 'k'); }
  std::filesystem::permissions(
      key, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
               std::filesystem::perms::group_read | std::filesystem::perms::others_read);
  FILE* pipe = popen(("timeout 30 " + test::ProgramCommand(binary) +
                      " run --lcm-url memq:// --source sim --auth-key " + key + " 2>&1")
                         .c_str(),
                     "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  std::filesystem::remove(key);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  EXPECT_NE(output.find(key + ": auth key: mode 0644"), std::string::npos) << output;
  EXPECT_NE(output.find("chmod 600"), std::string::npos) << output;
}

}  // namespace
}  // namespace h4::cam
