// The corner residual map (see corner_residual_map.h).
#include "host/validation/corner_residual_map.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <variant>

#include <spdlog/fmt/fmt.h>

#include "common/camera/board_pose_fit.h"
#include "host/identification/camera_parameters.h"
#include "host/identification/corner_cost.h"
#include "host/identification/corner_identification.h"
#include "host/identification/identified_robot.h"
#include "host/identification/parameter_vector.h"

namespace h4::host {

CameraIntrinsics PredictingCamera(const IdentificationResult& result, const CameraIntrinsics& file) {
  if (!result.camera) return file;
  const ResultCamera& refined = *result.camera;
  if (refined.distortion_model != ToString(file.distortion_model) ||
      refined.width != file.width || refined.height != file.height) {
    throw std::invalid_argument(fmt::format(
        "the Model {} result's camera ({} {}x{}) is not the camera file's ({} {}x{})",
        ToString(result.model), refined.distortion_model, refined.width, refined.height,
        ToString(file.distortion_model), file.width, file.height));
  }
  const std::vector<std::string> names = CameraParameterNames(file);
  if (refined.parameters.size() != names.size()) {
    throw std::invalid_argument(fmt::format(
        "the Model {} result's camera has {} parameters, the camera file's model {}",
        ToString(result.model), refined.parameters.size(), names.size()));
  }
  Eigen::VectorXd values(static_cast<Eigen::Index>(names.size()));
  for (size_t i = 0; i < names.size(); ++i) {
    if (refined.parameters[i].name != names[i]) {
      throw std::invalid_argument(fmt::format("the Model {} result's camera parameter {} is {}, "
                                              "the camera file's order has {}",
                                              ToString(result.model), i + 1,
                                              refined.parameters[i].name, names[i]));
    }
    values[static_cast<Eigen::Index>(i)] = refined.parameters[i].value;
  }
  return WithCameraParameters(file, values);
}

namespace {

std::vector<DatasetRow> RowsNotRejected(const IdentificationResult& result,
                                        const std::vector<DatasetRow>& rows) {
  const std::set<int64_t> rejected(result.rejected_poses.begin(), result.rejected_poses.end());
  std::vector<DatasetRow> kept;
  for (const DatasetRow& row : rows) {
    if (rejected.count(row.pose_id) == 0) kept.push_back(row);
  }
  return kept;
}

// Accumulates residuals into the grid and the inner / outer rings.
class Binning {
 public:
  explicit Binning(CornerResidualMap* map) : map_(map) {
    map_->cells.resize(static_cast<size_t>(map_->columns * map_->rows));
    for (int r = 0; r < map_->rows; ++r) {
      for (int c = 0; c < map_->columns; ++c) {
        map_->cells[static_cast<size_t>(r * map_->columns + c)].column = c;
        map_->cells[static_cast<size_t>(r * map_->columns + c)].row = r;
      }
    }
    sums_.assign(map_->cells.size(), Eigen::Vector3d::Zero());
  }

  void Add(const Eigen::Vector2d& uv, const Eigen::Vector2d& residual) {
    const int c = std::clamp(static_cast<int>(std::floor(uv.x() / map_->width * map_->columns)),
                             0, map_->columns - 1);
    const int r = std::clamp(static_cast<int>(std::floor(uv.y() / map_->height * map_->rows)),
                             0, map_->rows - 1);
    const size_t k = static_cast<size_t>(r * map_->columns + c);
    ++map_->cells[k].corners;
    sums_[k] += Eigen::Vector3d(residual.x(), residual.y(), residual.squaredNorm());
    const Eigen::Vector2d centre(0.5 * map_->width, 0.5 * map_->height);
    const bool inner = (uv - centre).norm() < 0.5 * centre.norm();
    (inner ? inner_ : outer_) += Eigen::Vector2d(residual.squaredNorm(), 1.0);
    ++map_->corners;
  }

  void Finish() {
    for (size_t k = 0; k < map_->cells.size(); ++k) {
      CornerResidualCell& cell = map_->cells[k];
      if (cell.corners == 0) continue;
      cell.mean_px = sums_[k].head<2>() / cell.corners;
      cell.rms_px = std::sqrt(sums_[k].z() / (2.0 * cell.corners));
    }
    const auto rms = [](const Eigen::Vector2d& s) {
      return s.y() > 0 ? std::sqrt(s.x() / (2.0 * s.y())) : 0.0;
    };
    map_->inner_rms_px = rms(inner_);
    map_->outer_rms_px = rms(outer_);
    map_->rms_px = rms(inner_ + outer_);
  }

 private:
  CornerResidualMap* map_;
  std::vector<Eigen::Vector3d> sums_;  ///< per cell: sum of residual x, y, |residual|^2
  Eigen::Vector2d inner_ = Eigen::Vector2d::Zero(), outer_ = Eigen::Vector2d::Zero();
};

// The board in words: what a wrong --board differs by.
std::string DescribeBoard(const BoardModel& board) {
  if (const auto* grid = std::get_if<AprilGridSpec>(&board.spec())) {
    return fmt::format("an AprilTag grid of {}x{} {} tags of {:g} mm, spacing {:g}", grid->cols,
                       grid->rows, grid->tag_family, grid->tag_size * 1e3, grid->tag_spacing);
  }
  const auto& chess = std::get<CheckerboardSpec>(board.spec());
  return fmt::format("a chessboard of {}x{} inner corners, {:g} x {:g} mm", chess.cols, chess.rows,
                     chess.col_spacing * 1e3, chess.row_spacing * 1e3);
}

// A map whose residuals are far beyond any camera error is not a camera model's misfit:
// validate drew 126-432 px with a wrong --board as "where the camera model misfits".
void RequireCornersMatchTheBoard(const CornerResidualMap& map, const BoardModel& board) {
  if (map.rms_px <= kBoardMismatchRmsPx) return;
  throw std::invalid_argument(fmt::format(
      "the corners miss their prediction by {:.0f} px RMS per axis over {} poses, far beyond "
      "any camera error (over {:g} px): they do not match the board given ({}; corners measured "
      "on another board?) or the camera file: check --board and --camera",
      map.rms_px, map.poses, kBoardMismatchRmsPx, DescribeBoard(board)));
}

}  // namespace

std::string CornerResidualPatternAdvice(const CornerResidualMap& map) {
  double weighted_mean_sq = 0.0;
  double largest_mean = 0.0;
  for (const CornerResidualCell& cell : map.cells) {
    weighted_mean_sq += cell.corners * cell.mean_px.squaredNorm() / 2.0;  // per axis
    largest_mean = std::max(largest_mean, cell.mean_px.norm());
  }
  const double pattern_rms = map.corners > 0 ? std::sqrt(weighted_mean_sq / map.corners) : 0.0;
  const std::string figures = fmt::format(
      "corner residuals {:.3f} px RMS per axis within half the half-diagonal of the image "
      "centre, {:.3f} px beyond; cell means {:.3f} px RMS, up to {:.3f} px",
      map.inner_rms_px, map.outer_rms_px, pattern_rms, largest_mean);
  if (map.outer_rms_px > 1.5 * map.inner_rms_px && pattern_rms > 0.5 * map.rms_px) {
    return "The corners show the camera model misfitting the lens (" + figures +
           ": they grow toward the image's edges). Calibrate the intrinsics again "
           "(h4cam calibrate-intrinsics) with views reaching the image's corners, or with a lens "
           "model of more terms; the report's camera section maps the pattern.";
  }
  if (pattern_rms > 0.5 * map.rms_px) {
    return "The corners show a pattern over the image (" + figures +
           "): the camera model misfits (focal length, principal point): check the camera "
           "file is the one of this camera and focus, and calibrate its intrinsics again if "
           "it is; the report's camera section maps the pattern.";
  }
  return "The corners show no pattern over the image (" + figures +
         "): not the camera model, the robot or the mounts: check that the robot is rigid and "
         "settled at every pose (backlash, flexure) and that the camera and board are fixed.";
}

CornerResidualMap ComputeCornerResidualMap(const IdentificationResult& result,
                                           const Assembly& assembly,
                                           const std::vector<DatasetRow>& rows,
                                           const std::vector<CornerObservation>& observed,
                                           const BoardModel& board,
                                           const CameraIntrinsics& file_camera, int columns,
                                           int grid_rows) {
  if (columns < 1 || grid_rows < 1) {
    throw std::invalid_argument("the corner residual map needs a grid of at least 1 x 1");
  }
  CornerResidualMap map;
  map.refined_camera = result.camera.has_value();
  map.model = result.model;
  map.width = file_camera.width;
  map.height = file_camera.height;
  map.columns = columns;
  map.rows = grid_rows;
  const CameraIntrinsics camera = PredictingCamera(result, file_camera);
  const IdentifiedRobot robot = RebuildFromResult(result, assembly);
  ParameterVector p(*robot.model, robot.X_BC, robot.X_TE);
  p.AppendCameraBlock(CameraParameterNames(camera), CameraParameterValues(camera));

  const std::vector<DatasetRow> kept = RowsNotRejected(result, rows);
  // Unit weights: the cost's residuals are then pixels (predicted - measured).
  std::vector<PoseCorners> corners = GroupCornersByRow(kept, observed, board, 1.0);
  for (PoseCorners& pose : corners) std::fill(pose.weight.begin(), pose.weight.end(), 1.0);
  Binning binning(&map);
  map.poses_left_out = static_cast<int>(rows.size() - kept.size());
  for (size_t j = 0; j < kept.size(); ++j) {
    if (corners[j].uv.empty()) continue;
    CornerCost cost(*robot.model, {kept[j]}, {corners[j]}, camera);
    Eigen::VectorXd r;
    if (!cost.Evaluate(p, &r, nullptr)) {
      ++map.poses_left_out;
      continue;
    }
    ++map.poses;
    for (size_t k = 0; k < corners[j].uv.size(); ++k) {
      const Eigen::Index i = 2 * static_cast<Eigen::Index>(k);
      binning.Add(corners[j].uv[k], -r.segment<2>(i));
    }
  }
  if (map.corners == 0) {
    throw std::invalid_argument(
        "no corner of the corners file could be predicted: none belongs to a dataset pose the "
        "result kept");
  }
  binning.Finish();
  RequireCornersMatchTheBoard(map, board);
  return map;
}

}  // namespace h4::host
