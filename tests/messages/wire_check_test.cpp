// The layout check that runs before lcm-gen's decode() (messages/bus/wire_check.h): every
// layout matches the generated encoder, and the lengths that make decode() throw, overflow
// or allocate gigabytes (string length 0, negative, INT32_MIN; joint_count -1 or 2^31-1)
// are refused, as are random mutations that decode() could not read back exactly.
#include "messages/bus/wire_check.h"

#include <climits>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "messages/bus/lcm_bus.h"
#include "messages/bus/wire_layouts.h"
#include "tests/messages/wire_bytes.h"

namespace h4::bus {
namespace {

using wire_bytes::Encode;
using wire_bytes::FullBoardPose;
using wire_bytes::PutBigEndian32;

template <class Msg>
bool Accepted(const std::vector<uint8_t>& bytes, std::string* why = nullptr) {
  std::string reason;
  const bool ok =
      CheckEncodedMessage(bytes.data(), bytes.size(), LayoutOf<Msg>(), WireLimits{}, &reason);
  if (why) *why = reason;
  return ok;
}

h4msgs::joint_state_t SampleJointState(int joints) {
  h4msgs::joint_state_t m{};
  m.utime = 1700000000000000;
  m.pose_id = 1;
  m.joint_count = joints;
  m.position.assign(static_cast<size_t>(joints), 0.25);
  m.settled = true;
  return m;
}

h4msgs::camera_status_t SampleCameraStatus() {
  h4msgs::camera_status_t m{};
  m.utime = 1;
  m.camera_id = "sim";
  m.last_error = "device timeout";
  return m;
}

h4msgs::board_corners_t SampleBoardCorners(int corners) {
  h4msgs::board_corners_t m{};
  m.utime = 1700000000000000;
  m.pose_id = 3;
  m.camera_id = "sim";
  m.corner_count = corners;
  const auto n = static_cast<size_t>(corners);
  m.tag_id.assign(n, 2);
  m.corner.assign(n, 9);
  m.u.assign(n, 640.5);
  m.v.assign(n, 480.25);
  m.sigma_px.assign(n, 0.02);
  return m;
}

// Byte offsets of the length fields in FullBoardPose (wire_bytes.h) and the samples above
// (after the 8-byte fingerprint).
constexpr size_t kBoardPoseCameraIdLength = 8 + 8 + 8;
constexpr size_t kJointStateCount = 8 + 8 + 8;
constexpr size_t kCameraStatusCameraIdLength = 8 + 8;
constexpr size_t kBoardCornersCount = 8 + 8 + 8 + 4 + 4;  // camera_id "sim": length, 3 bytes, NUL

TEST(WireCheck, EveryLayoutAcceptsWhatTheGeneratedEncoderWrites) {
  std::string why;
  EXPECT_TRUE(Accepted<h4msgs::board_pose_t>(Encode(FullBoardPose()), &why)) << why;
  h4msgs::board_pose_t empty_strings = FullBoardPose();
  empty_strings.camera_id.clear();
  empty_strings.board_id.clear();
  EXPECT_TRUE(Accepted<h4msgs::board_pose_t>(Encode(empty_strings), &why)) << why;
  for (int joints : {0, 1, 4, 64}) {
    EXPECT_TRUE(Accepted<h4msgs::joint_state_t>(Encode(SampleJointState(joints)), &why))
        << joints << ": " << why;
  }
  EXPECT_TRUE(Accepted<h4msgs::camera_status_t>(Encode(SampleCameraStatus()), &why)) << why;
  EXPECT_TRUE(Accepted<h4msgs::capture_request_t>(Encode(h4msgs::capture_request_t{}), &why))
      << why;
  EXPECT_TRUE(Accepted<h4msgs::robot_target_t>(Encode(h4msgs::robot_target_t{}), &why)) << why;
  EXPECT_TRUE(Accepted<h4msgs::sim_board_truth_t>(Encode(h4msgs::sim_board_truth_t{}), &why))
      << why;
  h4msgs::target_status_t refusal{};
  refusal.status = h4msgs::target_status_t::STATUS_UNREACHABLE;
  refusal.reason = std::string(1000, 'x');
  EXPECT_TRUE(Accepted<h4msgs::target_status_t>(Encode(h4msgs::target_status_t{}), &why)) << why;
  EXPECT_TRUE(Accepted<h4msgs::target_status_t>(Encode(refusal), &why)) << why;
  // A board has more corners than a joint state has joints: the corners' own bound.
  for (int corners : {0, 1, 144, kMaxBoardCorners}) {
    EXPECT_TRUE(Accepted<h4msgs::board_corners_t>(Encode(SampleBoardCorners(corners)), &why))
        << corners << ": " << why;
  }
}

TEST(WireCheck, RefusesCornerCountsBeyondTheirBound) {
  for (int32_t count : {-1, INT_MIN, kMaxBoardCorners + 1, INT_MAX}) {
    std::vector<uint8_t> bytes = Encode(SampleBoardCorners(4));
    PutBigEndian32(&bytes, kBoardCornersCount, count);
    std::string why;
    EXPECT_FALSE(Accepted<h4msgs::board_corners_t>(bytes, &why)) << count;
    EXPECT_NE(why.find("tag_id"), std::string::npos) << why;
  }
  std::string why;
  EXPECT_FALSE(
      Accepted<h4msgs::board_corners_t>(Encode(SampleBoardCorners(kMaxBoardCorners + 1)), &why));
}

TEST(WireCheck, RefusesAnotherTypesFingerprintAndTrailingOrMissingBytes) {
  std::vector<uint8_t> bytes = Encode(FullBoardPose());
  EXPECT_FALSE(Accepted<h4msgs::camera_status_t>(bytes));
  for (size_t size = 0; size < bytes.size(); ++size) {
    const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(size));
    EXPECT_FALSE(Accepted<h4msgs::board_pose_t>(cut)) << "cut at " << size;
  }
  bytes.push_back(0);
  std::string why;
  EXPECT_FALSE(Accepted<h4msgs::board_pose_t>(bytes, &why));
  EXPECT_NE(why.find("after the last field"), std::string::npos) << why;
}

TEST(WireCheck, RefusesStringLengthsThatMakeDecodeThrowOrOverflow) {
  for (int32_t length : {0, -1, -100, INT_MIN, INT_MAX, 5000}) {
    std::vector<uint8_t> pose = Encode(FullBoardPose());
    PutBigEndian32(&pose, kBoardPoseCameraIdLength, length);
    std::string why;
    EXPECT_FALSE(Accepted<h4msgs::board_pose_t>(pose, &why)) << length;
    EXPECT_NE(why.find("camera_id"), std::string::npos) << why;

    std::vector<uint8_t> status = Encode(SampleCameraStatus());
    PutBigEndian32(&status, kCameraStatusCameraIdLength, length);
    EXPECT_FALSE(Accepted<h4msgs::camera_status_t>(status)) << length;
  }
}

TEST(WireCheck, RefusesJointCountsThatMakeDecodeThrowOrAllocate) {
  for (int32_t count : {-1, INT_MIN, 65, INT_MAX, 1 << 28}) {
    std::vector<uint8_t> bytes = Encode(SampleJointState(4));
    PutBigEndian32(&bytes, kJointStateCount, count);
    std::string why;
    EXPECT_FALSE(Accepted<h4msgs::joint_state_t>(bytes, &why)) << count;
    EXPECT_NE(why.find("position"), std::string::npos) << why;
  }
}

TEST(WireCheck, RefusesAStringWithoutItsNul) {
  std::vector<uint8_t> bytes = Encode(FullBoardPose());
  const size_t length = FullBoardPose().camera_id.size() + 1;
  bytes[kBoardPoseCameraIdLength + 4 + length - 1] = 'x';
  std::string why;
  EXPECT_FALSE(Accepted<h4msgs::board_pose_t>(bytes, &why));
  EXPECT_NE(why.find("NUL"), std::string::npos) << why;
}

TEST(WireCheck, LimitsAreValidatedAndApplied) {
  WireLimits limits;
  std::string why;
  EXPECT_TRUE(limits.IsValid(&why));
  limits.max_string_bytes = 0;
  EXPECT_FALSE(limits.IsValid(&why));
  EXPECT_NE(why.find("max_string_bytes"), std::string::npos);
  EXPECT_THROW(LcmBus("memq://", limits), std::invalid_argument);

  WireLimits small;
  small.max_message_bytes = 100;
  const std::vector<uint8_t> bytes = Encode(FullBoardPose());
  EXPECT_FALSE(CheckEncodedMessage(bytes.data(), bytes.size(), LayoutOf<h4msgs::board_pose_t>(),
                                   small, &why));
  EXPECT_NE(why.find("more than the 100"), std::string::npos) << why;
}

// Random byte flips, length rewrites and cuts of valid encodings: DecodeMessage never
// throws, and whatever it accepts encodes back to exactly the bytes received.
template <class Msg>
void FuzzDecode(const std::vector<uint8_t>& valid, uint32_t seed, int* accepted, int* refused) {
  std::mt19937 rng(seed);
  for (int round = 0; round < 3000; ++round) {
    std::vector<uint8_t> bytes = valid;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const size_t at = rng() % bytes.size();
      switch (rng() % 4) {
        case 0:
          bytes[at] = static_cast<uint8_t>(rng());
          break;
        case 1:
          if (at + 4 <= bytes.size()) PutBigEndian32(&bytes, at, static_cast<int32_t>(rng()));
          break;
        case 2:
          bytes.resize(at);
          break;
        default:
          bytes.insert(bytes.begin() + static_cast<long>(at), uint8_t(rng()));
          break;
      }
    }
    std::string why;
    std::optional<Msg> msg;
    ASSERT_NO_THROW(msg = DecodeMessage<Msg>(bytes.data(), bytes.size(), WireLimits{}, &why));
    if (!msg) {
      ++*refused;
      continue;
    }
    ++*accepted;
    EXPECT_EQ(Encode(*msg), bytes) << "round " << round;
  }
}

TEST(WireCheck, RandomMutationsNeverThrowAndWhatIsAcceptedIsExact) {
  int accepted = 0, refused = 0;
  FuzzDecode<h4msgs::board_pose_t>(Encode(FullBoardPose()), 1, &accepted, &refused);
  FuzzDecode<h4msgs::joint_state_t>(Encode(SampleJointState(4)), 2, &accepted, &refused);
  FuzzDecode<h4msgs::camera_status_t>(Encode(SampleCameraStatus()), 3, &accepted, &refused);
  // Both branches exercised: the mutations are not all fatal nor all harmless.
  EXPECT_GT(accepted, 100);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace h4::bus
