// Where the camera model misfits (the report's camera section, after mrcal's residual
// maps): every board corner the camera measured, predicted from the pose's joint readings
// through the identified robot, X_BC, X_TE and the camera
// (common/README.md#identification-from-corners, the corner residual r_jQ without its weight),
// binned over the image. A model that fits leaves noise in every cell; a wrong camera model leaves
// a pattern: mean residuals that turn about the centre (focal length, distortion) or shift one way
// (principal point), growing towards the edges.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/board/board_model.h"
#include "common/camera/camera_intrinsics.h"
#include "common/formats/corners_csv.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/kinematics/robot_description.h"

namespace h4::host {

/// One cell of the image grid.
struct CornerResidualCell {
  int column = 0;
  int row = 0;
  int corners = 0;
  Eigen::Vector2d mean_px = Eigen::Vector2d::Zero();  ///< measured - predicted, px
  double rms_px = 0.0;                                ///< per-axis RMS of the residuals
};

struct CornerResidualMap {
  /// Which intrinsics predicted the corners: the corner path's refined ones, or the camera
  /// file's (a pose-path result).
  bool refined_camera = false;
  ModelKind model = ModelKind::k12;  ///< the result that predicted them
  int width = 0;                     ///< image, px
  int height = 0;
  int columns = 0;  ///< grid cells across and down
  int rows = 0;
  std::vector<CornerResidualCell> cells;  ///< row-major, every cell (empty ones have 0 corners)
  int poses = 0;                          ///< with corners, predicted
  int poses_left_out = 0;                 ///< rejected by the result, or forward kinematics failed
  int corners = 0;
  double rms_px = 0.0;  ///< per-axis RMS over every corner
  /// Per-axis RMS of the corners within half the half-diagonal of the image centre, and
  /// beyond it: a camera model that misfits grows towards the edges.
  double inner_rms_px = 0.0;
  double outer_rms_px = 0.0;
};

/// The intrinsics that predict the corners: the result's refined ones when it has them (its
/// `camera` key, checked against the file's model, size and parameter names; throws
/// std::invalid_argument naming what differs), else the file's.
CameraIntrinsics PredictingCamera(const IdentificationResult& result, const CameraIntrinsics& file);

/// The largest per-axis corner residual RMS a map may show, px: a camera model's misfit
/// (a wrong focal length, distortion, principal point) leaves a few pixels, a calibration
/// gone wrong tens; a wrong board (another tag size or spacing) leaves hundreds (issue 42,
/// defect 17: 126-432 px were drawn as the camera's misfit).
inline constexpr double kBoardMismatchRmsPx = 50.0;

/// The map of `result` (its model rebuilt with `assembly`) on the dataset `rows` and their
/// `observed` corners on `board`. `file_camera` gives the camera model, size and skew, and
/// the intrinsics unless the result carries refined ones (its `camera` key). Poses the
/// result rejected are left out. Throws std::invalid_argument when the result's camera
/// does not match the file's (model, size), when no corner belongs to a dataset row, on
/// a grid under 1 x 1, or when the residual RMS exceeds kBoardMismatchRmsPx (the message
/// names the board: the corners do not match it or the camera file).
CornerResidualMap ComputeCornerResidualMap(const IdentificationResult& result,
                                           const Assembly& assembly,
                                           const std::vector<DatasetRow>& rows,
                                           const std::vector<CornerObservation>& observed,
                                           const BoardModel& board,
                                           const CameraIntrinsics& file_camera, int columns = 16,
                                           int grid_rows = 12);

/// What the corner residuals' pattern over the image points to, for a fit the model cannot
/// describe (issue 43 point 7): residuals that grow toward the edges (outer RMS over 1.5x the
/// inner) point to the lens model; cell means that stand out of the noise everywhere (their
/// corner-weighted RMS over half the residual RMS) to the focal length or principal point;
/// neither, to the robot or the mounts rather than the camera model. One or two sentences
/// with the figures.
std::string CornerResidualPatternAdvice(const CornerResidualMap& map);

}  // namespace h4::host
