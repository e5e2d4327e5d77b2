// Tag recall against the truth, for the tests and benchmarks of detection through wide-angle
// lenses (issue 28): a board placed by where its centre is seen (off-axis angle, azimuth,
// distance, roll, tilt), which of its tags image wholly inside the frame at the true pose,
// and which of those a detection found, each corner where the truth puts it. The expected
// tags and corner positions come from the camera model and the true pose only.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/geometry/rigid_transform.h"
#include "common/units.h"
#include "firmware/detection/board_detector.h"

namespace h4::cam::bench {

// Where a scene puts the board: the direction of its centre from the camera (angle off the
// optical axis and azimuth about it from +u toward +v, deg), its distance (m), and its
// roll about its normal and tilt about its x axis (deg); facing the camera otherwise.
struct Scene {
  const char* name;
  double off_axis_deg, azimuth_deg, distance, roll_deg, tilt_deg;
};

inline RigidTransform BoardFacingCamera(const BoardModel& board, const Scene& scene) {
  const double a = RadiansFromDegrees(scene.off_axis_deg),
               phi = RadiansFromDegrees(scene.azimuth_deg);
  const Eigen::Vector3d n(std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a));
  const Eigen::Vector3d x0 = Eigen::Vector3d::UnitY().cross(n).normalized();
  Eigen::Matrix3d R0;
  R0 << x0, n.cross(x0), n;  // z of T (into the board) along the line of sight
  const Eigen::Matrix3d R_CT =
      R0 *
      Eigen::AngleAxisd(RadiansFromDegrees(scene.roll_deg), Eigen::Vector3d::UnitZ())
          .toRotationMatrix() *
      Eigen::AngleAxisd(RadiansFromDegrees(scene.tilt_deg), Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  Eigen::Vector3d p_TM = Eigen::Vector3d::Zero();  // middle of the board
  for (const Eigen::Vector3d& p_TQ : board.corners()) p_TM += p_TQ;
  p_TM /= static_cast<double>(board.corners().size());
  return RigidTransform(R_CT, scene.distance * n - R_CT * p_TM);
}

// Whether points along the whole outer border of tag `index` image at least `margin_px`
// inside the image at the true pose.
inline bool TagWhollyInImage(const BoardModel& board, const CameraModel& camera,
                             const RigidTransform& X_CT, int index, double margin_px) {
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d& a = board.corners()[static_cast<size_t>(4 * index + k)];
    const Eigen::Vector3d& b = board.corners()[static_cast<size_t>(4 * index + (k + 1) % 4)];
    for (int step = 0; step < 16; ++step) {
      Eigen::Vector2d uv;
      if (!camera.ProjectRay(X_CT * (a + step / 16.0 * (b - a)), &uv)) return false;
      if (uv.x() < margin_px || uv.y() < margin_px || uv.x() > camera.width() - 1 - margin_px ||
          uv.y() > camera.height() - 1 - margin_px) {
        return false;
      }
    }
  }
  return true;
}

struct TagCount {
  int expected = 0;   ///< tags wholly in the image
  int found = 0;      ///< of those, found with every corner near the truth
  int misplaced = 0;  ///< tags reported with a corner far from the truth (wrong tags)
};

// A corner farther from the truth than a third of its tag's shortest side is on another
// tag or is another corner: a wrong tag. (Corner precision is not this test's subject: the
// X-corners of large tags bent by strong distortion are still off by 1.5-3 px, which
// board_detector_test and the Kalibr corner work measure.)
inline double WrongCornerPx(const BoardModel& board, const CameraModel& camera,
                            const RigidTransform& X_CT, int index) {
  double shortest = 1e9;
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector2d a, b;
    if (!camera.ProjectRay(X_CT * board.corners()[static_cast<size_t>(4 * index + k)], &a) ||
        !camera.ProjectRay(X_CT * board.corners()[static_cast<size_t>(4 * index + (k + 1) % 4)],
                           &b)) {
      return 0;
    }
    shortest = std::min(shortest, (a - b).norm());
  }
  return shortest / 3;
}

// Counts a detection against the truth: a tag counts as found when all its reported
// corners are within WrongCornerPx of the true projection.
inline TagCount CountTags(const BoardModel& board, const CameraModel& camera,
                          const RigidTransform& X_CT, const BoardDetection& detection) {
  const int tags = board.corner_count() / 4;
  std::vector<int> good(static_cast<size_t>(tags), 0), bad(static_cast<size_t>(tags), 0);
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector2d uv;
    const bool near = camera.ProjectRay(X_CT * c.p_TQ, &uv) &&
                      (uv - c.uv).norm() < WrongCornerPx(board, camera, X_CT, c.id / 4);
    ++(near ? good : bad)[static_cast<size_t>(c.id / 4)];
  }
  TagCount count;
  for (int index = 0; index < tags; ++index) {
    const size_t i = static_cast<size_t>(index);
    count.misplaced += bad[i] > 0 ? 1 : 0;
    if (!TagWhollyInImage(board, camera, X_CT, index, 3.0)) continue;
    ++count.expected;
    count.found += good[i] > 0 && bad[i] == 0 ? 1 : 0;
  }
  return count;
}

}  // namespace h4::cam::bench
