// The robot controller's answer to a target (messages/target_status_t.lcm, H4_TARGET_STATUS):
// built by the simulated robot, read by the campaign, which skips a refused pose at once
// with the robot's reason instead of waiting out the settle timeout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <h4msgs/target_status_t.hpp>

namespace h4::host {

/// Bytes of `reason` sent on the wire (the wire check allows 4096 per string).
inline constexpr size_t kMaxTargetReasonBytes = 1000;

/// An answer to the target of `pose_id`; `reason` cut to kMaxTargetReasonBytes.
h4msgs::target_status_t MakeTargetStatus(int64_t utime, int64_t pose_id, int8_t status,
                                         const std::string& reason);

/// What a refusal says, for the console and the skipped-pose list, e.g. "unreachable: pose
/// (...) is out of reach ..."; nullopt when the target was accepted. The reason comes from
/// the network: anything but printable ASCII is shown as '?', so it cannot drive the
/// terminal.
std::optional<std::string> DescribeRefusal(const h4msgs::target_status_t& msg);

}  // namespace h4::host
