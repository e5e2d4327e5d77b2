// Validate(): the paper's IV.D experiments from files already read (see validation.h).
#include "host/validation/validation.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "host/identification/identified_robot.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"

namespace h4::host {
namespace {

void CheckModel(const std::optional<IdentificationResult>& result, ModelKind expected) {
  if (result && result->model != expected) {
    throw std::invalid_argument(fmt::format(
        "the result given for Model {} is a Model {} result (pass it as the Model {} one)",
        ToString(expected), ToString(result->model), ToString(result->model)));
  }
}

// Whether any of `rows` was a calibration pose of a given result: figures on it are then
// in-sample, whatever the dataset's set column says.
bool AnyInAFit(const ValidationInputs& in, const std::vector<DatasetRow>& rows) {
  for (const auto* result : {&in.result12, &in.result31}) {
    if (!*result) continue;
    const std::vector<int64_t>& calib = (*result)->calib_poses;
    for (const DatasetRow& row : rows) {
      if (std::find(calib.begin(), calib.end(), row.pose_id) != calib.end()) return true;
    }
  }
  return false;
}

// The held-out rows: those the result lists as "valid", else the dataset's set column, else
// (a result cross-validated on every pose) every row. Rows that were in a fit make the
// report in-sample, with a note saying so.
std::vector<DatasetRow> HeldOutRows(const ValidationInputs& in, ValidationReport* report) {
  const IdentificationResult* result = in.result12 ? &*in.result12 : nullptr;
  if (!result && in.result31) result = &*in.result31;
  std::vector<DatasetRow> held;
  if (result && !result->valid_poses.empty()) {
    for (int64_t id : result->valid_poses) {
      bool found = false;
      for (const DatasetRow& row : in.rows) {
        if (row.pose_id == id) {
          held.push_back(row);
          found = true;
          break;
        }
      }
      if (!found) {
        throw std::invalid_argument(fmt::format(
            "{}: pose {} is missing, but the Model {} result holds it out for validation "
            "(is this the dataset it was identified from?)",
            in.dataset_name, id, ToString(result->model)));
      }
    }
  } else {
    for (const DatasetRow& row : in.rows) {
      if (row.set == PoseSet::kValid) held.push_back(row);
    }
  }
  if (held.empty() && result && !result->cross_validation) {
    throw std::invalid_argument(fmt::format(
        "{}: no held-out pose (the result lists none and no row has set=valid)", in.dataset_name));
  }
  if (held.empty()) {
    // Every pose was in the fit and k-fold cross-validation gave the held-out figures
    // (each model's cross_validation): the tables below are then over every pose, in-sample.
    held = in.rows;
    report->in_sample = true;
    report->notes.push_back(
        "every pose was in the fit: Table 3 and the positioning error are over every pose, "
        "in-sample; the held-out figures are the k-fold cross-validated ones (summary, verdict)");
  } else if (AnyInAFit(in, held)) {
    report->in_sample = true;
    report->notes.push_back(
        "the poses marked for validation were in a result's fit (its calib_poses): Table 3 and "
        "the positioning error on them are in-sample");
  }
  for (const DatasetRow& row : held) report->heldout_ids.push_back(row.pose_id);
  return held;
}

bool Near(double a, double b) { return std::abs(a - b) < 1e-9; }

bool SameModel12(const Model12Parameters& a, const Model12Parameters& b) {
  bool same = Near(a.h, b.h) && Near(a.arm, b.arm) && Near(a.forearm, b.forearm) && Near(a.R, b.R);
  for (int i = 0; i < 4; ++i) same = same && Near(a.alpha[i], b.alpha[i]) && Near(a.q0[i], b.q0[i]);
  return same;
}

// The result whose base frame a measured run is judged in: the model that drove it, else
// (the a priori controller, which has no camera placement of its own) Model 12's, else 31's.
const IdentificationResult& FrameOfRun(const ValidationInputs& in, const MeasuredSquareInput& m) {
  const auto given = [&in](ModelKind kind) -> const std::optional<IdentificationResult>& {
    return kind == ModelKind::k12 ? in.result12 : in.result31;
  };
  if (m.driven_by) {
    if (!given(*m.driven_by)) {
      throw std::invalid_argument(fmt::format(
          "the measured square \"{}\" was driven by {}: its square is judged in that model's "
          "base frame, give its result (--result{})",
          m.label, ModelLabel(*m.driven_by), ToString(*m.driven_by)));
    }
    return *given(*m.driven_by);
  }
  if (in.result12) return *in.result12;
  if (in.result31) return *in.result31;
  throw std::invalid_argument(fmt::format(
      "the measured square \"{}\" needs an identified result (--result12 or --result31): its "
      "camera and board placement X_BC, X_TE turn the measured board poses into end-effector "
      "poses",
      m.label));
}

// The measured square runs: the board poses through the placement of the model that drove
// each (FrameOfRun).
std::vector<MeasuredSquareRun> MeasuredSquares(const ValidationInputs& in) {
  std::vector<MeasuredSquareRun> runs;
  if (in.square_measured.empty()) return runs;
  if (!in.square_plan) {
    throw std::invalid_argument(
        "the measured square runs need the plan they were driven through (--square-plan)");
  }
  std::set<std::string> labels;
  for (const MeasuredSquareInput& m : in.square_measured) {
    if (!labels.insert(m.label).second) {
      throw std::invalid_argument(
          fmt::format("two measured square runs are labelled \"{}\"", m.label));
    }
    const IdentificationResult& frame = FrameOfRun(in, m);
    MeasuredSquareRun run =
        MeasuredSquareOf(*in.square_plan, m.rows, CameraInPlanFrame(frame, in.apriori.model12),
                         frame.X_TE, m.label, m.dataset_name);
    run.frame = frame.model;
    run.own_frame = m.driven_by == frame.model;
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace

std::string EvaluatedPosesLabel(const ValidationReport& report) {
  const size_t n = report.heldout_ids.size();
  return report.in_sample ? fmt::format("in-sample ({} poses, none held out of the fit)", n)
                          : fmt::format("held out ({} poses not in the fit)", n);
}

std::string CrossValidatedLabel(const CrossValidationFigures& cv) {
  return fmt::format("{}-fold cross-validated (held-out) RMS over {} poses", cv.folds, cv.poses);
}

bool IsPaperScenario(const RobotDescription& apriori, const SimulationTruth& truth) {
  return !truth.robot.model31 && SameModel12(apriori.model12, kPaperAprioriModel12) &&
         SameModel12(truth.robot.model12, kPaperIdentifiedModel12);
}

double ValidationReport::StraightnessImprovementPercent(size_t m, size_t r) const {
  if (models.empty() || m >= models.size() || r >= models[0].straightness.size() ||
      r >= models[m].straightness.size()) {
    return 0.0;
  }
  const double before = models[0].straightness[r].fit.rms_distance;
  const double after = models[m].straightness[r].fit.rms_distance;
  return before > 0.0 ? 100.0 * (before - after) / before : 0.0;
}

namespace {

// A model to validate: its label, kinematics and camera / board placement, and the result
// it was rebuilt from (none for the a priori).
struct Candidate {
  std::string label;
  std::unique_ptr<KinematicModel> model;
  RigidTransform X_BC, X_TE;
  const IdentificationResult* result = nullptr;
};

void CheckInputs(const ValidationInputs& in) {
  CheckModel(in.result12, ModelKind::k12);
  CheckModel(in.result31, ModelKind::k31);
  if (!in.result12 && !in.result31) {
    throw std::invalid_argument("validation needs an identification result (Model 12 or 31)");
  }
  if (in.rows.empty()) throw std::invalid_argument(in.dataset_name + ": no pose");
}

// Notes on the square runs measured by the camera: planned points missing, rows not planned.
void NoteMeasuredSquareGaps(const std::vector<MeasuredSquareRun>& runs,
                            std::vector<std::string>* notes) {
  for (const MeasuredSquareRun& m : runs) {
    if (!m.missing_ids.empty()) {
      notes->push_back(fmt::format(
          "square (measured), {} controller: {} of {} planned points missing from {} (pose ids "
          "{}); the side errors use the others",
          m.label, m.missing_ids.size(), m.planned, m.dataset_name, PoseIdList(m.missing_ids)));
    }
    if (m.unplanned_rows > 0) {
      notes->push_back(fmt::format(
          "square (measured), {} controller: {} rows of {} are not in the plan (ignored)", m.label,
          m.unplanned_rows, m.dataset_name));
    }
  }
}

// The a priori robot, then each identified result. "Before calibration" isolates the
// kinematic parameters: the a priori Model 12 with the placement the Model 12
// identification found (the a priori placement, off by centimetres, would measure the
// camera set-up instead of the robot).
std::vector<Candidate> CandidatesToValidate(const ValidationInputs& in,
                                            std::vector<std::string>* notes) {
  std::vector<Candidate> candidates;
  Candidate apriori{"a priori", std::make_unique<Model12>(in.apriori.model12, in.apriori.assembly),
                    in.apriori.X_BC, in.apriori.X_TE};
  if (in.result12) {
    apriori.X_BC = in.result12->X_BC;
    apriori.X_TE = in.result12->X_TE;
  } else {
    notes->push_back(
        "no Model 12 result: the a priori row uses the a priori camera and board placement");
  }
  candidates.push_back(std::move(apriori));
  for (const auto* result : {&in.result12, &in.result31}) {
    if (!*result) continue;
    IdentifiedRobot robot = RebuildFromResult(**result, in.apriori.assembly);
    candidates.push_back(
        {ModelLabel((*result)->model), std::move(robot.model), robot.X_BC, robot.X_TE, &**result});
  }
  return candidates;
}

// A note per identified model without an accuracy map: its result has no covariance.
void NoteMissingAccuracyMaps(const ValidationReport& report, std::vector<std::string>* notes) {
  for (size_t m = 1; m < report.models.size(); ++m) {
    if (report.models[m].accuracy_map) continue;
    notes->push_back(report.models[m].label +
                     ": no accuracy map (the result has no parameter_covariance: written by an "
                     "older h4cal, or the covariance could not be computed)");
  }
}

// The true robot of a simulation, or null with a note on what is then not computed.
std::unique_ptr<KinematicModel> TrueModel(const ValidationInputs& in, ValidationReport* report) {
  if (in.truth) {
    report->has_truth = true;
    report->paper_scenario = IsPaperScenario(in.apriori, *in.truth);
    return in.truth->robot.MakeModel();
  }
  report->notes.push_back(
      in.square_measured.empty()
          ? "no truth file: the square path needs the true robot (simulation), not computed"
          : "no truth file: the simulated square path needs the true robot, not computed "
            "(the measured square runs are shown)");
  return nullptr;
}

// The rows in `result`'s fit: its calib_poses, or (a result that does not list them) the
// rows not held out.
std::vector<DatasetRow> FitRows(const std::vector<DatasetRow>& rows,
                                const IdentificationResult& result,
                                const std::vector<DatasetRow>& held) {
  std::vector<DatasetRow> fit;
  for (const DatasetRow& row : rows) {
    const auto& calib = result.calib_poses;
    const bool listed = std::find(calib.begin(), calib.end(), row.pose_id) != calib.end();
    const bool is_held = std::any_of(held.begin(), held.end(),
                                     [&](const DatasetRow& h) { return h.pose_id == row.pose_id; });
    if (calib.empty() ? !is_held : listed) fit.push_back(row);
  }
  return fit;
}

// Where `model` puts each row: the forward kinematics of its joint readings, from the
// workspace centre; rows where it fails are left out (they are in no figure of the map).
std::vector<EePose> PosesOfRows(const KinematicModel& model, const std::vector<DatasetRow>& rows) {
  std::vector<EePose> poses;
  for (const DatasetRow& row : rows) {
    const FkResult fk =
        ForwardKinematics(model, JointVector(row.q[0], row.q[1], row.q[2], row.q[3]));
    if (fk.ok()) poses.push_back(fk.x);
  }
  return poses;
}

// The paper's 81 grid poses in B, where the true accuracy is measured.
std::vector<EePose> GridPoses() {
  std::vector<EePose> poses;
  for (const PlannedPose& p : GridPosePlan()) poses.push_back(p.x);
  return poses;
}

// One candidate's figures: joint residuals (held-out and all poses), positioning error,
// straightness runs and, for a Model 12 with the true robot known, the square path.
ModelValidation ValidateCandidate(const ValidationInputs& in, const Candidate& c,
                                  const std::vector<DatasetRow>& held,
                                  const KinematicModel* true_model) {
  ModelValidation v;
  v.label = c.label;
  v.heldout = JointResidualsOf(*c.model, c.X_BC, c.X_TE, held);
  if (v.heldout.poses == 0) {
    throw std::invalid_argument(fmt::format(
        "{}: no held-out pose is within the reach of the {} model", in.dataset_name, c.label));
  }
  v.all = JointResidualsOf(*c.model, c.X_BC, c.X_TE, in.rows);
  v.positioning = PositioningErrorOf(*c.model, c.X_BC, c.X_TE, held);
  for (size_t r = 0; r < in.straightness.size(); ++r) {
    StraightnessRun run = StraightnessOf(*c.model, in.straightness[r]);
    if (!run.ok) {
      throw std::invalid_argument(
          fmt::format("straightness run {} with the {} model: {}", r + 1, c.label, run.message));
    }
    v.straightness.push_back(std::move(run));
  }
  if (true_model != nullptr && c.model->kind() == ModelKind::k12) {
    v.square = RunSquare(*c.model, {true_model, in.truth->robot.X_ModelB()}, in.square);
  }
  if (c.result != nullptr) {
    v.calibration_poses = PosesOfRows(*c.model, FitRows(in.rows, *c.result, held));
    if (!AnyInAFit(in, held)) v.evaluated_poses = PosesOfRows(*c.model, held);
    v.cross_validation = c.result->cross_validation;
    if (in.truth) v.true_accuracy = TrueAccuracyOfResult(*c.result, in.truth->robot, GridPoses());
    v.accuracy_map = AccuracyMapOfResult(*c.result, in.apriori.assembly);
    if (c.result->parameter_covariance_camera_exact) {
      IdentificationResult camera_exact = *c.result;
      camera_exact.parameter_covariance = c.result->parameter_covariance_camera_exact;
      v.accuracy_map_camera_exact = AccuracyMapOfResult(camera_exact, in.apriori.assembly);
    }
  }
  return v;
}

// The corner residual map of the result that best knows the camera: one whose intrinsics
// the corner path refined (Model 31 before 12), else a pose-path result through the file.
std::optional<CornerResidualMap> CornerResidualsOf(const ValidationInputs& in,
                                                   std::vector<std::string>* notes) {
  if (in.corners.empty()) {
    notes->push_back(
        "no corners given (--corners, --board, --camera): the camera section has no residual "
        "map");
    return std::nullopt;
  }
  if (!in.board || !in.camera) {
    throw std::invalid_argument("the corners need their board and camera file (--board, --camera)");
  }
  const IdentificationResult* chosen = nullptr;
  for (const auto* r : {&in.result31, &in.result12}) {
    if (chosen == nullptr && r->has_value() && (*r)->camera) chosen = &**r;
  }
  for (const auto* r : {&in.result31, &in.result12}) {
    if (chosen == nullptr && r->has_value()) chosen = &**r;
  }
  return ComputeCornerResidualMap(*chosen, in.apriori.assembly, in.rows, in.corners, *in.board,
                                  *in.camera);
}

}  // namespace

ValidationReport Validate(const ValidationInputs& in) {
  CheckInputs(in);
  ValidationReport report;
  // The measured squares first: their input errors need no kinematics to be found.
  report.measured_squares = MeasuredSquares(in);
  NoteMeasuredSquareGaps(report.measured_squares, &report.notes);
  const std::vector<DatasetRow> held = HeldOutRows(in, &report);
  const std::vector<Candidate> candidates = CandidatesToValidate(in, &report.notes);
  const std::unique_ptr<KinematicModel> true_model = TrueModel(in, &report);
  if (in.straightness.empty()) {
    report.notes.push_back("no straightness run given: Table 4 not computed");
  }
  for (const Candidate& c : candidates) {
    report.models.push_back(ValidateCandidate(in, c, held, true_model.get()));
  }
  NoteMissingAccuracyMaps(report, &report.notes);
  report.corner_residuals = CornerResidualsOf(in, &report.notes);
  const Candidate& apriori = candidates.front();
  report.apriori_all = PositioningErrorOf(*apriori.model, apriori.X_BC, apriori.X_TE, in.rows);
  report.prior = AnalyzeRotationAxis(in.rows, in.apriori.X_BC, in.apriori.X_TE);
  if (!report.prior.ok) report.notes.push_back("4-DoF check: " + report.prior.message);
  return report;
}

}  // namespace h4::host
