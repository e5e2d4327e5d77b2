// The camera service's line per measurement; see measurement_summary.h.
#include "firmware/service/measurement_summary.h"

#include <set>

#include <spdlog/fmt/fmt.h>

#include "common/units.h"

namespace h4::cam {
namespace {

int DistinctTags(const std::vector<MeasuredCorner>& corners) {
  std::set<int> tags;
  for (const MeasuredCorner& corner : corners) {
    if (corner.tag_id >= 0) tags.insert(corner.tag_id);
  }
  return static_cast<int>(tags.size());
}

std::string WhatWasSeen(const Measurement& m) {
  const int tags = DistinctTags(m.corners);
  // A chessboard has no tags: its corners alone say what was seen.
  return tags > 0 ? fmt::format("{} tags, {} corners", tags, m.corners_used)
                  : fmt::format("{} corners", m.corners_used);
}

}  // namespace

std::string MeasurementSummary(const Measurement& m) {
  std::string text = ToString(m.status);
  const bool has_pose =
      m.status == Measurement::Status::kOk || m.status == Measurement::Status::kMoved;
  if (!has_pose) return m.message.empty() ? text : text + " (" + m.message + ")";
  text += fmt::format(
      ": {}, RMS {:.2f} px, spread {:.2f} px over {} frames, board {:.3f} m away, sigma "
      "{:.4f} mm / {:.4f} deg per axis",
      WhatWasSeen(m), m.rms_px, m.frame_spread_px, m.frames_averaged, m.X_CT.translation().norm(),
      1e3 * m.sigma_t, DegreesFromRadians(m.sigma_r));
  if (!m.message.empty()) text += " (" + m.message + ")";
  return text;
}

}  // namespace h4::cam
