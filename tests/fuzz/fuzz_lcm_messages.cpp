// Fuzz target: every LCM type of messages/ as the bus adapter receives it. The first byte
// picks the type, the rest is the encoded message: it is decoded directly
// (bus::DecodeMessage: the layout check of wire_check.h, then lcm-gen's decode) and
// published raw on that type's channel of an in-process bus (memq://) subscribed to every
// type, whose Handle() must return without throwing. A message that decodes must encode
// back to the same bytes.
#include <spdlog/spdlog.h>

#include "messages/bus/lcm_bus.h"
#include "messages/channels.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using h4::bus::LcmBus;

template <class Msg>
void DecodeAndEncodeBack(const uint8_t* data, size_t size) {
  std::string why;
  const std::optional<Msg> msg = h4::bus::DecodeMessage<Msg>(data, size, {}, &why);
  if (!msg) {
    h4::fuzz::Require(!why.empty(), "a refused message says why");
    return;
  }
  const int encoded_size = msg->getEncodedSize();
  h4::fuzz::Require(encoded_size == static_cast<int>(size), "a decoded message has its size");
  std::vector<uint8_t> encoded(size);
  h4::fuzz::Require(msg->encode(encoded.data(), 0, encoded_size) == encoded_size,
                    "a decoded message encodes");
  h4::fuzz::Require(std::equal(encoded.begin(), encoded.end(), data),
                    "a decoded message encodes back to the bytes received");
}

template <class Msg>
void SubscribeIgnoring(LcmBus& bus, const char* channel) {
  bus.Subscribe<Msg>(channel, [](const Msg&) {});
}

// One bus for the whole run: LCM's set-up is far slower than one message.
LcmBus& Bus() {
  static LcmBus* bus = [] {
    spdlog::set_level(spdlog::level::off);  // the adapter logs each refused message
    auto* b = new LcmBus("memq://");
    SubscribeIgnoring<h4msgs::board_pose_t>(*b, h4::channels::kBoardPose);
    SubscribeIgnoring<h4msgs::camera_status_t>(*b, h4::channels::kCameraStatus);
    SubscribeIgnoring<h4msgs::capture_request_t>(*b, h4::channels::kCaptureRequest);
    SubscribeIgnoring<h4msgs::joint_state_t>(*b, h4::channels::kJointState);
    SubscribeIgnoring<h4msgs::robot_target_t>(*b, h4::channels::kRobotTarget);
    SubscribeIgnoring<h4msgs::sim_board_truth_t>(*b, h4::channels::kSimBoardTruth);
    return b;
  }();
  return *bus;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t* message = data + 1;
  const size_t message_size = size - 1;
  const char* channel = nullptr;
  switch (data[0] % 6) {
    case 0:
      DecodeAndEncodeBack<h4msgs::board_pose_t>(message, message_size);
      channel = h4::channels::kBoardPose;
      break;
    case 1:
      DecodeAndEncodeBack<h4msgs::camera_status_t>(message, message_size);
      channel = h4::channels::kCameraStatus;
      break;
    case 2:
      DecodeAndEncodeBack<h4msgs::capture_request_t>(message, message_size);
      channel = h4::channels::kCaptureRequest;
      break;
    case 3:
      DecodeAndEncodeBack<h4msgs::joint_state_t>(message, message_size);
      channel = h4::channels::kJointState;
      break;
    case 4:
      DecodeAndEncodeBack<h4msgs::robot_target_t>(message, message_size);
      channel = h4::channels::kRobotTarget;
      break;
    default:
      DecodeAndEncodeBack<h4msgs::sim_board_truth_t>(message, message_size);
      channel = h4::channels::kSimBoardTruth;
      break;
  }
  LcmBus& bus = Bus();
  bus.lcm().publish(channel, message, static_cast<unsigned int>(message_size));
  const int handled = bus.Handle(std::chrono::milliseconds(0));
  h4::fuzz::Require(handled == 1, "the bus dispatches the message it was given");
  return 0;
}
