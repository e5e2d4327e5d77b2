// The square path measured by the camera (paper IV.D, last experiment, on a real robot): the
// plan of commanded points (`h4cal square-plan`, a common/formats/README.md poses CSV), the robot
// driven through them by an IK control law, Model 12 or 31 (`h4cal collect --plan --controller`),
// and the board measured at each point (a paired dataset CSV with the plan's pose ids). The
// measured end-effector position is the translation of X_BE = X_BC * X_CT * X_TE (eq. (6)), with
// the placement X_BC, X_TE of a Model 12 identification; the side errors are those of the simulated
// run (square_path.h, SquareErrorsOf).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/geometry/rigid_transform.h"
#include "host/kinematics/model_kind.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/poses_csv.h"
#include "host/validation/square_path.h"

namespace h4::host {

/// The commanded points of a square as poses CSV rows (X_BE targets in B, theta the square's
/// angle), in SquarePoints order, ids first_id, first_id + 1, ... Throws
/// std::invalid_argument when the options are invalid.
std::vector<EndEffectorPoseRow> SquarePlanPoses(const SquareOptions& options, int64_t first_id);

/// A square plan read back: the square it describes and each point's side.
struct SquarePlan {
  SquareOptions options;                   ///< the square the points describe
  std::vector<int64_t> pose_ids;           ///< in path order
  std::vector<Eigen::Vector3d> commanded;  ///< target positions in B, m (as in the file)
  std::vector<int> side;                   ///< side of each point, 0..3
};

/// Recognises the rows SquarePlanPoses writes (same order; any ids): 4 sides of the same
/// number (>= 2) of points, one theta, every point where the square's generator puts it
/// (within 1 um). Throws std::invalid_argument naming `source_name`, the row and what was
/// expected.
SquarePlan SquarePlanFromPoses(const std::vector<EndEffectorPoseRow>& rows,
                               const std::string& source_name);

struct MeasuredSquareRun {
  std::string label;                 ///< the controller that drove the robot, e.g. "a priori"
  std::string dataset_name;          ///< for messages and the report
  /// The identified model whose base frame the square is judged in (its camera and board
  /// placement turn the board poses into end-effector positions), and whether that model
  /// drove the run. In its own frame the offset is the model's absolute error; in another
  /// model's it also holds the two base frames' difference, which no measurement separates.
  ModelKind frame = ModelKind::k12;
  bool own_frame = false;
  SquareRun run;                     ///< over the measured points (reached = measured)
  size_t planned = 0;                ///< points in the plan
  std::vector<int64_t> missing_ids;  ///< plan points with no row in the dataset (skipped)
  size_t unplanned_rows = 0;         ///< dataset rows whose pose_id is not in the plan (ignored)
};

/// The measured square: for each plan point with a dataset row of the same pose_id, the
/// measured position p_BE of X_BC * X_CT * X_TE. Throws std::invalid_argument naming the
/// dataset and the side when a side has fewer than 2 measured points.
MeasuredSquareRun MeasuredSquareOf(const SquarePlan& plan, const std::vector<DatasetRow>& rows,
                                   const RigidTransform& X_BC, const RigidTransform& X_TE,
                                   const std::string& label, const std::string& dataset_name);

/// "1001, 1002, 1005" (at most `limit` ids, then ", ... (N in all)").
std::string PoseIdList(const std::vector<int64_t>& ids, size_t limit = 12);

}  // namespace h4::host
