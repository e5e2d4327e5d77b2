// IPPE starts for a planar board's pose; see planar_pose_starts.h.
#include "firmware/detection/planar_pose_starts.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace h4::cam {

std::vector<RigidTransform> IppePlanarStarts(const std::vector<CornerObservation>& corners,
                                             const CameraModel& camera) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const CornerObservation& c : corners) {
    Eigen::Vector2d xn;
    if (!camera.NormalizedFromPixel(c.uv, &xn)) continue;
    object.emplace_back(c.p_TQ.x(), c.p_TQ.y(), c.p_TQ.z());
    image.emplace_back(xn.x(), xn.y());
  }
  if (object.size() < 4) return {};
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    cv::solvePnPGeneric(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvecs, tvecs, false,
                        cv::SOLVEPNP_IPPE);
  } catch (const cv::Exception&) {
    return {};  // degenerate configuration (collinear points): no start
  }
  std::vector<RigidTransform> starts;
  for (size_t k = 0; k < rvecs.size(); ++k) {
    cv::Mat R_cv;
    cv::Rodrigues(rvecs[k], R_cv);
    Eigen::Matrix3d R_CT;
    Eigen::Vector3d p_CT;
    cv::cv2eigen(R_cv, R_CT);
    cv::cv2eigen(tvecs[k], p_CT);
    starts.emplace_back(R_CT, p_CT);
  }
  return starts;
}

}  // namespace h4::cam
