// The sim source's capture poses; see sim_capture_poses.h.
#include "firmware/sources/sim_capture_poses.h"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>

#include <Eigen/Geometry>

#include "common/board/board_model.h"
#include "common/camera/camera_model.h"
#include "common/units.h"

namespace h4::cam {
namespace {

/// The board seen across these fractions of the image width at the two depths (near,
/// far): large enough to reach the image's edges, small enough to fit tilted.
constexpr std::array<double, 2> kWidthSpanned = {0.5, 0.35};
/// Kept inside the image: the pattern and this much of the white border around it, as a
/// fraction of the pattern's larger side (the chessboard detector needs a white frame).
constexpr double kBorderKept = 0.05;
constexpr double kImageMarginPx = 3.0;

/// The 3 x 3 grid cells (column, row), corners first: an image edge in the first frames.
constexpr std::array<std::array<int, 2>, 9> kCellOrder = {
    {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {1, 0}, {2, 1}, {1, 2}, {0, 1}}};

double FractionalPart(double x) { return x - std::floor(x); }

/// Tilt 15-40 deg about an axis in the board plane turning by the golden angle, then up to
/// 15 deg about the optical axis.
Eigen::Matrix3d BoardOrientation(int index) {
  const double golden_fraction = 0.5 * (3.0 - std::sqrt(5.0));  // 0.382: the golden angle
  const double tilt = RadiansFromDegrees(15.0 + 25.0 * FractionalPart(0.5 + index * 0.618034));
  const double azimuth = 2.0 * std::numbers::pi * golden_fraction * index;
  const double roll = RadiansFromDegrees(15.0 * std::sin(2.3 * index));
  const Eigen::Vector3d axis(std::cos(azimuth), std::sin(azimuth), 0.0);
  return (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, axis))
      .toRotationMatrix();
}

/// The board outline kept in view (kBorderKept), four corners in the board frame T.
std::array<Eigen::Vector3d, 4> KeptOutline(const BoardModel& model) {
  const Eigen::Vector2d size = model.pattern_max() - model.pattern_min();
  const Eigen::Vector2d grow = Eigen::Vector2d::Constant(kBorderKept * size.maxCoeff());
  const Eigen::Vector2d lo = model.pattern_min() - grow, hi = model.pattern_max() + grow;
  return {Eigen::Vector3d(lo.x(), lo.y(), 0), Eigen::Vector3d(hi.x(), lo.y(), 0),
          Eigen::Vector3d(hi.x(), hi.y(), 0), Eigen::Vector3d(lo.x(), hi.y(), 0)};
}

bool OutlineInImage(const CameraModel& camera, const RigidTransform& X_CT,
                    const std::array<Eigen::Vector3d, 4>& outline) {
  for (const Eigen::Vector3d& p_TQ : outline) {
    Eigen::Vector2d uv;
    if (!camera.ProjectVisible(X_CT * p_TQ, &uv)) return false;
    if (uv.x() < kImageMarginPx || uv.y() < kImageMarginPx ||
        uv.x() > camera.width() - 1 - kImageMarginPx ||
        uv.y() > camera.height() - 1 - kImageMarginPx) {
      return false;
    }
  }
  return true;
}

/// The largest fraction in [start, 1] for which `fits` holds, by bisection (`fits(start)`
/// holds; the farther out, the less of the board fits).
double FarthestFitting(double start, const std::function<bool(double)>& fits) {
  if (fits(1.0)) return 1.0;
  double inside = start, outside = 1.0;
  for (int step = 0; step < 20; ++step) {
    const double middle = 0.5 * (inside + outside);
    if (fits(middle)) {
      inside = middle;
    } else {
      outside = middle;
    }
  }
  return inside;
}

/// X_CT with R_CT and the board centre on the ray of pixel `uv` at depth `depth`.
RigidTransform PoseAimedAt(const CameraIntrinsics& camera, const Eigen::Matrix3d& R_CT,
                           const Eigen::Vector3d& p_T_centre, const Eigen::Vector2d& uv,
                           double depth) {
  const Eigen::Vector3d ray((uv.x() - camera.K(0, 2)) / camera.K(0, 0),
                            (uv.y() - camera.K(1, 2)) / camera.K(1, 1), 1.0);
  return RigidTransform(R_CT, depth * ray - R_CT * p_T_centre);
}

}  // namespace

RigidTransform SimCapturePose(const BoardSpec& board, const CameraIntrinsics& camera, int index) {
  const BoardModel model(board);
  const CameraModel camera_model(camera);
  const Eigen::Vector2d pattern_size = model.pattern_max() - model.pattern_min();
  const Eigen::Vector2d centre = 0.5 * (model.pattern_min() + model.pattern_max());
  const Eigen::Vector3d p_T_centre(centre.x(), centre.y(), 0.0);
  const double depth = pattern_size.maxCoeff() * camera.K(0, 0) /
                       (kWidthSpanned[index % 2] * static_cast<double>(camera.width));
  const Eigen::Matrix3d R_CT = BoardOrientation(index);
  const auto& cell = kCellOrder[index % kCellOrder.size()];
  const Eigen::Vector2d image_centre(0.5 * camera.width, 0.5 * camera.height);
  // As far out towards the cell's image edges as the board fits: along the diagonal, then
  // along each axis in turn (a board stopped by the bottom edge slides on to the left).
  const Eigen::Vector2d offset(cell[0] - 1, cell[1] - 1);
  const auto aimed = [&](const Eigen::Vector2d& fraction) {
    const Eigen::Vector2d uv =
        image_centre + fraction.cwiseProduct(offset).cwiseProduct(image_centre);
    return PoseAimedAt(camera, R_CT, p_T_centre, uv, depth);
  };
  const std::array<Eigen::Vector3d, 4> outline = KeptOutline(model);
  const auto fits = [&](const Eigen::Vector2d& fraction) {
    return OutlineInImage(camera_model, aimed(fraction), outline);
  };
  const double diagonal =
      FarthestFitting(0.0, [&](double f) { return fits(Eigen::Vector2d(f, f)); });
  const double across =
      FarthestFitting(diagonal, [&](double f) { return fits(Eigen::Vector2d(f, diagonal)); });
  const double down =
      FarthestFitting(diagonal, [&](double f) { return fits(Eigen::Vector2d(across, f)); });
  return aimed(Eigen::Vector2d(across, down));
}

}  // namespace h4::cam
