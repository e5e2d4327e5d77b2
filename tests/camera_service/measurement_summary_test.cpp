// The camera service's line per measurement (firmware/service/measurement_summary.h): what
// was seen and how well, not only "pose 25: ok" (issue 26 point 8).
#include "firmware/service/measurement_summary.h"

#include <gtest/gtest.h>

namespace h4::cam {
namespace {

Measurement SeenMeasurement() {
  Measurement m;
  m.status = Measurement::Status::kOk;
  m.X_CT = RigidTransform(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.0, 0.3, 0.4));
  for (int tag = 0; tag < 3; ++tag) {
    for (int corner = 0; corner < 4; ++corner) m.corners.push_back({tag, 4 * tag + corner});
  }
  m.corners_used = 12;
  m.rms_px = 0.123;
  m.frame_spread_px = 0.031;
  m.frames_averaged = 10;
  m.sigma_t = 4e-6;
  m.sigma_r = 3.6651914291880923e-05;  // 0.0021 deg
  return m;
}

TEST(MeasurementSummary, APoseSaysWhatWasSeenAndHowWell) {
  EXPECT_EQ(MeasurementSummary(SeenMeasurement()),
            "ok: 3 tags, 12 corners, RMS 0.12 px, spread 0.03 px over 10 frames, board 0.500 m "
            "away, sigma 0.0040 mm / 0.0021 deg per axis");
}

TEST(MeasurementSummary, AChessboardHasCornersAndNoTags) {
  Measurement m = SeenMeasurement();
  for (MeasuredCorner& corner : m.corners) corner.tag_id = -1;
  EXPECT_NE(MeasurementSummary(m).find("ok: 12 corners, RMS"), std::string::npos)
      << MeasurementSummary(m);
}

TEST(MeasurementSummary, NoPoseSaysWhy) {
  Measurement m;
  m.status = Measurement::Status::kNoBoard;
  m.message = "no tag found in 10 frames";
  EXPECT_EQ(MeasurementSummary(m),
            std::string(ToString(m.status)) + " (no tag found in 10 frames)");
}

}  // namespace
}  // namespace h4::cam
