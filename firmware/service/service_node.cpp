// The camera service on the bus; see service_node.h.
#include "firmware/service/service_node.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "firmware/service/sd_notify.h"
#include "messages/channels.h"

namespace h4::cam {

std::optional<RigidTransform> TruthPose(const h4msgs::sim_board_truth_t& truth, std::string* why) {
  Eigen::Vector3d p(truth.translation[0], truth.translation[1], truth.translation[2]);
  Eigen::Vector4d q(truth.quaternion[0], truth.quaternion[1], truth.quaternion[2],
                    truth.quaternion[3]);
  if (!p.allFinite() || !q.allFinite()) {
    if (why) *why = "translation or quaternion not finite";
    return std::nullopt;
  }
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    if (why) *why = fmt::format("quaternion norm {:f}, expected 1", q.norm());
    return std::nullopt;
  }
  return RigidTransform::FromTranslationQuaternion(p, q);
}

ServiceNode::ServiceNode(bus::LcmBus& bus, CameraService& service, ShowTruth show_truth,
                         std::chrono::duration<double> heartbeat_period)
    : bus_(bus),
      service_(service),
      show_truth_(std::move(show_truth)),
      heartbeats_(std::chrono::duration_cast<Clock::duration>(heartbeat_period)) {
  bus_.Subscribe<h4msgs::capture_request_t>(
      channels::kCaptureRequest,
      [this](const h4msgs::capture_request_t& request) { service_.SubmitRequest(request); });
  if (show_truth_) {
    bus_.Subscribe<h4msgs::sim_board_truth_t>(
        channels::kSimBoardTruth,
        [this](const h4msgs::sim_board_truth_t& truth) { OnTruth(truth); });
  }
}

void ServiceNode::OnTruth(const h4msgs::sim_board_truth_t& truth) {
  std::string why;
  std::optional<RigidTransform> X_CT = TruthPose(truth, &why);
  if (!X_CT) {
    ++invalid_truths_;
    spdlog::warn("sim truth for pose {} ignored: {} ({} ignored so far)", truth.pose_id, why,
                 invalid_truths_);
    return;
  }
  pending_truth_ = *X_CT;
}

void ServiceNode::PublishStatus() {
  if (bus_.Publish(channels::kCameraStatus, service_.Status(NowUtime()))) ++statuses_published_;
  NotifyWatchdog();
}

void ServiceNode::Poll(std::chrono::milliseconds timeout) {
  const Clock::time_point now = Clock::now();
  if (heartbeats_.Due(now)) PublishStatus();
  // While frames are wanted, the frame wait in Step() is the loop's pacing; otherwise
  // wait on the bus, but not past the next heartbeat.
  std::chrono::milliseconds wait(0);
  if (!service_.WantsFrames()) {
    const auto to_heartbeat =
        std::chrono::duration_cast<std::chrono::milliseconds>(*heartbeats_.next() - now);
    wait = std::max(std::chrono::milliseconds(0), std::min(timeout, to_heartbeat));
  }
  bus_.Handle(wait);
  if (pending_truth_) {
    show_truth_(*pending_truth_);
    pending_truth_.reset();
  }
  if (std::optional<h4msgs::board_pose_t> pose = service_.Step(Clock::now())) {
    if (bus_.Publish(channels::kBoardPose, *pose)) ++board_poses_published_;
    // Right after the pose it belongs to (messages/README.md, H4_BOARD_CORNERS).
    if (std::optional<h4msgs::board_corners_t> corners = service_.TakeCorners()) {
      if (bus_.Publish(channels::kBoardCorners, *corners)) ++board_corners_published_;
    }
  }
}

}  // namespace h4::cam
