// The robot's answer to a target; see target_status.h.
#include "host/campaign/target_status.h"

#include <algorithm>

namespace h4::host {
namespace {

using Status = h4msgs::target_status_t;

std::string PrintableAscii(const std::string& text) {
  std::string out = text.substr(0, kMaxTargetReasonBytes);
  std::replace_if(
      out.begin(), out.end(), [](char c) { return c < 0x20 || c > 0x7e; }, '?');
  return out;
}

// The kind of refusal a code names; "" for STATUS_REFUSED and codes no controller of ours
// sends, whose reason alone says what kind (still a refusal: the robot will not go there).
std::string RefusalKind(int8_t status) {
  switch (status) {
    case Status::STATUS_UNREACHABLE:
      return "unreachable";
    case Status::STATUS_OUTSIDE_LIMITS:
      return "outside joint limits";
    case Status::STATUS_INVALID:
      return "invalid target";
    default:
      return "";
  }
}

}  // namespace

h4msgs::target_status_t MakeTargetStatus(int64_t utime, int64_t pose_id, int8_t status,
                                         const std::string& reason) {
  h4msgs::target_status_t msg{};
  msg.utime = utime;
  msg.pose_id = pose_id;
  msg.status = status;
  msg.reason = reason.substr(0, kMaxTargetReasonBytes);
  return msg;
}

std::optional<std::string> DescribeRefusal(const h4msgs::target_status_t& msg) {
  if (msg.status == Status::STATUS_ACCEPTED) return std::nullopt;
  const std::string kind = RefusalKind(msg.status);
  const std::string reason = PrintableAscii(msg.reason);
  if (kind.empty()) return reason.empty() ? "no reason given" : reason;
  return reason.empty() ? kind : kind + ": " + reason;
}

}  // namespace h4::host
