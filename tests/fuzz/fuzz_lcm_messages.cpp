// Fuzz target: every LCM type of messages/ as the bus adapter receives it. The first byte
// picks the type, the rest is the encoded message: it is decoded directly
// (bus::DecodeMessage: the layout check of wire_check.h, then lcm-gen's decode) and
// published raw on that type's channel of an in-process bus (memq://) subscribed to every
// type, whose Handle() must return without throwing. A message that decodes must encode
// back to the same bytes.
#include <iterator>

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

/// One LCM type of messages/, on its channel.
struct FuzzedType {
  void (*subscribe_ignoring)(LcmBus&, const char*);
  void (*decode_and_encode_back)(const uint8_t*, size_t);
  const char* channel;
};

template <class Msg>
FuzzedType TypeOn(const char* channel) {
  return {SubscribeIgnoring<Msg>, DecodeAndEncodeBack<Msg>, channel};
}

// An input's first byte picks one, modulo their count.
const FuzzedType kFuzzedTypes[] = {
    TypeOn<h4msgs::board_pose_t>(h4::channels::kBoardPose),
    TypeOn<h4msgs::camera_status_t>(h4::channels::kCameraStatus),
    TypeOn<h4msgs::capture_request_t>(h4::channels::kCaptureRequest),
    TypeOn<h4msgs::joint_state_t>(h4::channels::kJointState),
    TypeOn<h4msgs::robot_target_t>(h4::channels::kRobotTarget),
    TypeOn<h4msgs::sim_board_truth_t>(h4::channels::kSimBoardTruth),
    TypeOn<h4msgs::board_corners_t>(h4::channels::kBoardCorners),
    TypeOn<h4msgs::target_status_t>(h4::channels::kTargetStatus),
};

// One bus for the whole run: LCM's set-up is far slower than one message.
LcmBus& Bus() {
  static LcmBus* bus = [] {
    spdlog::set_level(spdlog::level::off);  // the adapter logs each refused message
    auto* b = new LcmBus("memq://");
    for (const FuzzedType& type : kFuzzedTypes) type.subscribe_ignoring(*b, type.channel);
    return b;
  }();
  return *bus;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t* message = data + 1;
  const size_t message_size = size - 1;
  const FuzzedType& type = kFuzzedTypes[data[0] % std::size(kFuzzedTypes)];
  type.decode_and_encode_back(message, message_size);
  LcmBus& bus = Bus();
  bus.lcm().publish(type.channel, message, static_cast<unsigned int>(message_size));
  const int handled = bus.Handle(std::chrono::milliseconds(0));
  h4::fuzz::Require(handled == 1, "the bus dispatches the message it was given");
  return 0;
}
