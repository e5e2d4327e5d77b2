// Test helper for dataset rows, shared with the tests of the libraries that write datasets
// (tests/campaign): two datasets compared row by row, field by field.
#pragma once

#include <vector>

#include <gtest/gtest.h>

#include "host/formats/dataset_csv.h"

namespace h4 {

/// Expects `b` to hold the rows of `a`: every field equal, but the rotation of X_CT, which
/// travels as a quaternion (matrix -> quaternion -> matrix costs a few ulp), within
/// `rotation_tolerance` per element; 0 asks for the very same rotation (two files written
/// from the same measurements).
inline void ExpectSameRows(const std::vector<DatasetRow>& a, const std::vector<DatasetRow>& b,
                           double rotation_tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pose_id, b[i].pose_id);
    EXPECT_EQ(a[i].utime, b[i].utime);
    EXPECT_EQ(a[i].q, b[i].q);
    EXPECT_EQ(a[i].X_CT.translation(), b[i].X_CT.translation());
    if (rotation_tolerance == 0) {
      EXPECT_EQ(a[i].X_CT.rotation(), b[i].X_CT.rotation());
    } else {
      EXPECT_LT((a[i].X_CT.rotation() - b[i].X_CT.rotation()).cwiseAbs().maxCoeff(),
                rotation_tolerance);
    }
    EXPECT_EQ(a[i].set, b[i].set);
    EXPECT_EQ(a[i].sigma_t, b[i].sigma_t);
    EXPECT_EQ(a[i].sigma_r, b[i].sigma_r);
  }
}

}  // namespace h4
