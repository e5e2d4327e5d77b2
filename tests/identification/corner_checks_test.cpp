// The corner path's checks at its entry (host/identification/corner_checks.h, issue 42,
// defect 9): corners within the camera's image, degenerate poses left out, an overstated
// corner sigma named in the verdict.
#include "host/identification/corner_checks.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "host/identification/verdict.h"

namespace h4::host {
namespace {

CameraIntrinsics Camera1024x768() {
  CameraIntrinsics camera;
  camera.width = 1024;
  camera.height = 768;
  return camera;
}

std::vector<DatasetRow> Rows(int count) {
  std::vector<DatasetRow> rows(static_cast<size_t>(count));
  for (int j = 0; j < count; ++j) rows[static_cast<size_t>(j)].pose_id = j + 1;
  return rows;
}

std::string WhatOf(const std::vector<CornerObservation>& corners) {
  try {
    RequireCornersInImage(Rows(2), corners, Camera1024x768());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(CornerChecks, ACornerOffTheImageIsRefusedNamingItsPose) {
  std::vector<CornerObservation> corners = {{1, 0, 0, 100, 100, 0.1},
                                            {1, 0, 1, 1030, 760, 0.1},  // within the margin
                                            {2, 0, 0, 200, 100, 0.1},
                                            {2, 0, 1, 300, 100, 0.1}};
  EXPECT_EQ(WhatOf(corners), "");
  corners[1].u = 999999;
  EXPECT_NE(WhatOf(corners).find("pose 1: corner 1 (tag 0) at (999999, 760) px is outside the "
                                 "camera's 1024x768 image"),
            std::string::npos)
      << WhatOf(corners);
  corners[1].u = 100;
  corners[2].v = -2000;
  corners[3].v = 5000;
  EXPECT_NE(WhatOf(corners).find("pose 2: every one of its 2 corners is off"), std::string::npos)
      << WhatOf(corners);
  // Corners of poses that are not rows are not this dataset's: not judged.
  corners = {{7, 0, 0, 1e5, 1e5, 0.1}};
  EXPECT_EQ(WhatOf(corners), "");
}

TEST(CornerChecks, APoseWhoseCornersSitOnOnePixelOrLineIsLeftOut) {
  std::vector<PoseCorners> grouped(3);
  for (int k = 0; k < 12; ++k) {
    grouped[0].uv.emplace_back(100 + 10 * (k % 4), 200 + 10 * (k / 4));  // a grid: kept
    grouped[1].uv.emplace_back(500, 400);                                // one pixel
    grouped[2].uv.emplace_back(100 + 10 * k, 200 + 10 * k);              // one line
    for (PoseCorners& g : grouped) {
      g.p_TQ.emplace_back(0, 0, 0);
      g.weight.push_back(1);
    }
  }
  const std::vector<std::string> reasons = DropDegenerateCornerPoses(Rows(3), &grouped);
  ASSERT_EQ(reasons.size(), 2u);
  EXPECT_NE(reasons[0].find("pose 2: its 12 corners spread 0 px"), std::string::npos) << reasons[0];
  EXPECT_NE(reasons[1].find("pose 3:"), std::string::npos) << reasons[1];
  EXPECT_EQ(grouped[0].uv.size(), 12u);
  EXPECT_TRUE(grouped[1].uv.empty());
  EXPECT_TRUE(grouped[2].uv.empty());
}

TEST(CornerChecks, AnOverstatedCornerSigmaIsNotGood) {
  Verdict verdict = Verdict::kGood;
  IdentificationResult result;
  result.verdict = ResultVerdict{.code = "good", .text = "Good", .figures = {}};
  EXPECT_FALSE(FlagOverstatedCornerNoise(0.8, &verdict, &result));
  EXPECT_EQ(verdict, Verdict::kGood);
  EXPECT_TRUE(FlagOverstatedCornerNoise(2e-5, &verdict, &result));
  EXPECT_EQ(verdict, Verdict::kNoiseOverstated);
  EXPECT_EQ(result.verdict->code, "noise_overstated");
  EXPECT_NE(result.verdict->text.find("overstated"), std::string::npos);
}

}  // namespace
}  // namespace h4::host
