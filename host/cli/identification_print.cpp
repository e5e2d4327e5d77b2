// Printing an identification (see identification_print.h).
#include "host/cli/identification_print.h"

#include <fmt/core.h>

#include "common/units.h"

namespace h4::host::cli {
namespace {

// The verdict heads the output: what the technician acts on comes first.
void PrintVerdict(const IdentificationResult& r) {
  if (!r.verdict) return;
  fmt::print("VERDICT: {}\n  {}\n", r.verdict->code, r.verdict->text);
}

void PrintRejectedPoses(const IdentificationResult& r) {
  for (const RejectedPose& pose : r.rejected_details) {
    fmt::print("  rejected pose {}: score {:.3g}, {}\n", static_cast<long long>(pose.pose_id),
               pose.score, pose.reason);
  }
}

}  // namespace

void PrintAccuracyMapLine(const ModelValidation& identified) {
  if (!identified.accuracy_map) return;
  const AccuracyMap& map = *identified.accuracy_map;
  fmt::print(
      "  accuracy map: predicted 1-sigma position error median {:.4f} mm, largest {:.4f} mm "
      "over {} workspace poses\n",
      map.MedianPositionSigma() * 1e3, map.MaxPositionSigma() * 1e3, map.points.size());
}

void PrintHeadline(const IdentificationOutcome& outcome) {
  const IdentificationResult& r = outcome.result;
  PrintVerdict(r);
  fmt::print("Model {}, {} estimator: {}\n", ToString(r.model), r.estimator,
             outcome.summary.usable ? "converged" : "NOT converged");
  fmt::print("  poses: {} calibration, {} validation, {} rejected\n", r.calib_poses.size(),
             r.valid_poses.size(), r.rejected_poses.size());
  PrintRejectedPoses(r);
  if (r.condition_number) fmt::print("  condition number (scaled): {:.3g}\n", *r.condition_number);
  for (const FixedParameter& f : r.fixed) fmt::print("  fixed {}: {}\n", f.name, f.reason);
  fmt::print(
      "  joint residual RMS (deg), in-sample (calibration poses): {:.4f} {:.4f} {:.4f} {:.4f}\n",
      DegreesFromRadians(r.calib_rms_rad[0]), DegreesFromRadians(r.calib_rms_rad[1]),
      DegreesFromRadians(r.calib_rms_rad[2]), DegreesFromRadians(r.calib_rms_rad[3]));
  if (!r.valid_poses.empty()) {
    fmt::print(
        "  joint residual RMS (deg), held out ({} poses not in the fit): {:.4f} {:.4f} {:.4f} "
        "{:.4f}\n",
        r.valid_poses.size(), DegreesFromRadians(r.valid_rms_rad[0]),
        DegreesFromRadians(r.valid_rms_rad[1]), DegreesFromRadians(r.valid_rms_rad[2]),
        DegreesFromRadians(r.valid_rms_rad[3]));
  }
  if (r.valid_position_rms_m && r.valid_rotation_rms_rad) {
    fmt::print(
        "  board pose error, held out ({} poses not in the fit): {:.4f} mm, {:.4f} deg RMS\n",
        r.valid_poses.size(), 1e3 * *r.valid_position_rms_m,
        DegreesFromRadians(*r.valid_rotation_rms_rad));
  }
  if (r.cross_validation) {
    fmt::print(
        "  board pose error, {}-fold cross-validated (held-out) RMS over {} poses: {:.4f} mm, "
        "{:.4f} deg, normalised chi-square / dof {:.3g}\n",
        r.cross_validation->folds, r.cross_validation->poses,
        1e3 * r.cross_validation->position_rms_m,
        DegreesFromRadians(r.cross_validation->rotation_rms_rad), r.cross_validation->reduced_chi2);
  }
  // Where the robot goes is the figure to judge a calibration by; the board's position in
  // the camera frame is what the camera sees of it, and leaves out what the camera cannot
  // tell apart from the robot (its own placement, its scale).
  if (r.predicted_robot_accuracy_m) {
    fmt::print(
        "  predicted robot accuracy (1 sigma, end-effector positions at the calibration poses, "
        "base frame registered): {:.4f} mm\n",
        1e3 * *r.predicted_robot_accuracy_m);
  }
  if (r.predicted_position_accuracy_m) {
    fmt::print(
        "  predicted board position accuracy in the camera frame (1 sigma, calibration poses; "
        "not where the robot goes): {:.4f} mm\n",
        1e3 * *r.predicted_position_accuracy_m);
  }
  for (const CorrelatedPair& c : r.correlations) {
    fmt::print("  correlated: {} ~ {} ({:.3f})\n", c.a, c.b, c.correlation);
  }
  fmt::print("  {} iterations, {:.3f} s\n", outcome.summary.iterations, outcome.summary.seconds);
}

}  // namespace h4::host::cli
