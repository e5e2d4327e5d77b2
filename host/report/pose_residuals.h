// The per-pose residual table of the report and its CSV (`residuals.csv` beside report.html):
// for each pose of the dataset and each model (a priori, Model 12, Model 31), the joint
// residuals q~ - IK(X_BC X_CT X_TE) of paper Table 3, so that a technician finds the poses
// a model misfits and a script can read them all.
#pragma once

#include <string>

#include "host/validation/validation.h"

namespace h4::host {

/// CSV: pose_id, evaluated (1 when the pose is among Table 3's), then for each model
/// `<model>_q1_deg` .. `<model>_q4_deg` (model: apriori, model12, model31); an empty cell
/// where the model cannot reach the measured pose.
std::string PoseResidualsCsv(const ValidationReport& report);

/// HTML: the `rows` poses with the largest residual under the last model (the most
/// accurate one identified), each model's largest |residual| per pose, in deg.
std::string PoseResidualsTable(const ValidationReport& report, size_t rows = 10);

}  // namespace h4::host
