// Loading the validation inputs and the text summary (see validation_inputs.h).
#include "host/cli/validation_inputs.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/cli/shared_options.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "common/units.h"
#include "host/formats/poses_csv.h"
#include "host/identification/corner_identification.h"
#include "host/formats/robot_yaml.h"
#include "host/simulation/simulation_folder.h"

namespace h4::host::cli {
namespace {

namespace fs = std::filesystem;

// `explicit_path`, else `in_sim_dir` (the file's place in --sim-dir; "" without one) when
// it exists there (or when required).
std::string Resolve(const std::string& explicit_path, const std::string& in_sim_dir, bool required,
                    const std::string& option) {
  if (!explicit_path.empty()) return explicit_path;
  if (!in_sim_dir.empty() && (fs::exists(in_sim_dir) || required)) return in_sim_dir;
  if (required) throw std::invalid_argument(option + " is required (or --sim-dir)");
  return "";
}

void CheckExists(const std::string& path) {
  if (!path.empty() && !fs::exists(path)) throw std::invalid_argument(path + ": no such file");
}

std::optional<IdentificationResult> ReadResult(const std::string& path, ModelKind expected_model,
                                               const std::string& option) {
  if (path.empty()) return std::nullopt;
  CheckExists(path);
  IdentificationResult result = ReadIdentificationResult(path);
  if (result.model != expected_model) {
    throw std::invalid_argument(fmt::format("{}: a Model {} result given to {} (expected Model {})",
                                            path, ToString(result.model), option,
                                            ToString(expected_model)));
  }
  return result;
}

// The square plan and the measured runs; the plan also sets the simulated square.
void LoadSquareRuns(const ValidationFileOptions& o, const std::string& result12_path,
                    const std::string& result31_path, ValidationInputs* in) {
  if (o.square_measured.empty() != o.square_plan_path.empty()) {
    throw std::invalid_argument(
        o.square_measured.empty()
            ? "--square-plan is given without --square-measured LABEL=DATASET (the runs "
              "collected along it)"
            : "--square-measured needs --square-plan, the plan the runs were collected along");
  }
  if (o.square_measured.empty()) return;
  const auto has_result = [&](ModelKind kind) {
    return !(kind == ModelKind::k12 ? result12_path : result31_path).empty();
  };
  for (const std::string& value : o.square_measured) {
    const std::string label = SplitSquareMeasured(value).first;
    const std::optional<ModelKind> model = ModelDrivingSquare(label);
    if (model && !has_result(*model)) {
      throw std::invalid_argument(fmt::format(
          "--square-measured \"{}\" needs --result{}: a square {} drove is judged in {}'s "
          "base frame, through the camera and board placement (X_BC, X_TE) it identified",
          label, ToString(*model), ModelLabel(*model), ModelLabel(*model)));
    }
    if (!model && !has_result(ModelKind::k12) && !has_result(ModelKind::k31)) {
      throw std::invalid_argument(
          "--square-measured needs --result12 or --result31: an identified camera and board "
          "placement (X_BC, X_TE) turns the measured board poses into end-effector poses");
    }
  }
  CheckExists(o.square_plan_path);
  in->square_plan = SquarePlanFromPoses(ReadPosesCsv(o.square_plan_path), o.square_plan_path);
  const SquareOptions& planned = in->square_plan->options;
  if (o.square_mm_given && std::abs(o.square_mm * 1e-3 - planned.side) > 1e-6) {
    throw std::invalid_argument(
        fmt::format("--square-mm {} disagrees with the {:.3f} mm square of {} (leave it out)",
                    o.square_mm, planned.side * 1e3, o.square_plan_path));
  }
  in->square = planned;
  for (const std::string& value : o.square_measured) {
    const auto [label, path] = SplitSquareMeasured(value);
    CheckExists(path);
    in->square_measured.push_back({label, path, ReadDatasetCsv(path), ModelDrivingSquare(label)});
  }
}

// The corners with their board and camera, all three or none.
void LoadCorners(const ValidationFileOptions& o, ValidationInputs* in) {
  const int given = static_cast<int>(!o.corners_path.empty()) +
                    static_cast<int>(!o.board_path.empty()) +
                    static_cast<int>(!o.camera_path.empty());
  if (given == 0) return;
  if (given != 3) {
    throw std::invalid_argument(
        "--corners, --board and --camera go together: the corners h4cam measured, its board "
        "and the camera file it measured with");
  }
  in->corners = ReadCornersCsv(o.corners_path);
  RequireCornersOfDataset(in->rows, in->corners, o.corners_path);
  in->board.emplace(ReadBoardYaml(o.board_path));
  in->camera = ReadCameraYaml(o.camera_path);
}

}  // namespace

void AddValidationFileOptions(CLI::App* command, ValidationFileOptions* o) {
  command->add_option("--sim-dir", o->sim_dir,
                      "Folder written by `h4cal simulate` (+ result12.json, result31.json): "
                      "default for every file below");
  h4::cli::AddRobotOption(command, &o->robot_path);
  h4::cli::AddDataOption(command, &o->data_path);
  h4::cli::AddInputFileOption(command, "--result12", &o->result12_path,
                              "Model 12 identification result JSON");
  h4::cli::AddInputFileOption(command, "--result31", &o->result31_path,
                              "Model 31 identification result JSON");
  h4::cli::AddInputFileOption(command, "--truth", &o->truth_path,
                              "truth.yaml of a simulation: the true robot for the square path");
  command->add_option("--straightness", o->straightness_paths,
                      "Joints CSVs logged along a straight ruler, one per direction");
  command
      ->add_option("--square-mm", o->square_mm,
                   "Side of the simulated square path, mm (with --square-plan: the plan's)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->each([o](const std::string&) { o->square_mm_given = true; });
  h4::cli::AddInputFileOption(command, "--square-plan", &o->square_plan_path,
                              "Poses CSV of the square driven on the robot (h4cal square-plan); "
                              "also sets the simulated square");
  command
      ->add_option("--square-measured", o->square_measured,
                   "LABEL=DATASET, repeatable: dataset CSV collected along --square-plan by the "
                   "LABEL controller (e.g. \"a priori=sq_apriori.csv\"). LABEL \"Model 12\" or "
                   "\"Model 31\": that model drove it, and its square is judged in that model's "
                   "base frame (needs its --result12/--result31); another LABEL is judged in "
                   "the frame of --result12, else --result31")
      ->take_all();
  h4::cli::AddInputFileOption(command, "--corners", &o->corners_path,
                              "Corners CSV measured with the dataset's poses (h4cal collect, "
                              "h4cam measure --corners-out): the report's corner residual map; "
                              "needs --board and --camera");
  h4::cli::AddBoardOption(command, &o->board_path);
  h4::cli::AddCameraOption(command, &o->camera_path,
                           "Camera YAML h4cam measured with the corners (OpenCV, or Kalibr's "
                           "camchain.yaml#camN)");
}

std::optional<ModelKind> ModelDrivingSquare(const std::string& label) {
  std::string key;
  for (const char c : label) {
    if (c != ' ') key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (key.rfind("model", 0) == 0) key.erase(0, 5);
  return ParseModelKind(key);
}

std::string MeasuredSquareLines(const std::vector<MeasuredSquareRun>& runs) {
  std::string t;
  bool another_frame = false;
  for (const MeasuredSquareRun& m : runs) {
    const SquareRun& s = m.run;
    another_frame = another_frame || !m.own_frame;
    // The shape first: it needs no frame. The offset and the mean error depend on the frame.
    t += fmt::format(
        "Square (measured), {} controller, in {}'s base frame{}: shape {:.2f} mm (offset "
        "removed); side RMS {:.2f} {:.2f} {:.2f} {:.2f} mm, mean |measured - commanded| {:.2f} "
        "mm, offset ({:.2f}, {:.2f}, {:.2f}) mm; {} of {} points",
        m.label, ModelLabel(m.frame), m.own_frame ? " (its own)" : "", s.shape_rms * 1e3,
        s.sides[0].rms * 1e3, s.sides[1].rms * 1e3, s.sides[2].rms * 1e3, s.sides[3].rms * 1e3,
        s.mean_position_error * 1e3, s.offset[0] * 1e3, s.offset[1] * 1e3, s.offset[2] * 1e3,
        s.reached.size(), m.planned);
    t += (m.missing_ids.empty() ? "\n" : " (missing pose ids " + PoseIdList(m.missing_ids) + ")\n");
  }
  if (!runs.empty()) {
    t += "  offset: mean measured - commanded position. A square judged in the base frame of "
         "the model that drove it: that model's absolute error there.";
    t += another_frame ? " Judged in another model's frame (the a priori model has no camera "
                         "placement of its own): it also holds the difference between the two "
                         "base frames, which the camera cannot separate; compare shapes.\n"
                       : "\n";
  }
  return t;
}

std::pair<std::string, std::string> SplitSquareMeasured(const std::string& value) {
  const size_t eq = value.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == value.size()) {
    throw std::invalid_argument(fmt::format(
        "--square-measured \"{}\": expected LABEL=DATASET (e.g. \"Model 12=sq_m12.csv\")", value));
  }
  return {value.substr(0, eq), value.substr(eq + 1)};
}

ValidationInputs LoadValidationInputs(const ValidationFileOptions& o) {
  ValidationInputs in;
  const SimulationFolder sim{o.sim_dir};
  const bool has_sim = !o.sim_dir.empty();
  const std::string robot =
      Resolve(o.robot_path, has_sim ? sim.apriori_robot() : "", true, "--robot");
  const std::string data = Resolve(o.data_path, has_sim ? sim.dataset() : "", true, "--data");
  const std::string r12 =
      Resolve(o.result12_path, has_sim ? sim.result(ModelKind::k12) : "", false, "");
  const std::string r31 =
      Resolve(o.result31_path, has_sim ? sim.result(ModelKind::k31) : "", false, "");
  const std::string truth = Resolve(o.truth_path, has_sim ? sim.truth() : "", false, "");
  // The square runs first: a missing result is named before any file is read.
  in.square.side = o.square_mm * 1e-3;
  LoadSquareRuns(o, r12, r31, &in);
  for (const auto& path : {robot, data, truth}) CheckExists(path);
  in.apriori = ReadRobotYaml(robot);
  in.rows = ReadDatasetCsv(data);
  in.dataset_name = data;
  in.result12 = ReadResult(r12, ModelKind::k12, "--result12");
  in.result31 = ReadResult(r31, ModelKind::k31, "--result31");
  if (!in.result12 && !in.result31) {
    throw std::invalid_argument("give an identification result: --result12 and/or --result31");
  }
  if (!truth.empty()) in.truth = ReadTruthYaml(truth);
  LoadCorners(o, &in);
  std::vector<std::string> runs = o.straightness_paths;
  if (runs.empty() && has_sim) {
    for (int k = 1; fs::exists(sim.straightness(k)); ++k) {
      runs.push_back(sim.straightness(k));
    }
  }
  for (const auto& path : runs) {
    CheckExists(path);
    in.straightness.push_back(ReadJointsCsv(path));
    if (in.straightness.back().size() < 3) {
      throw std::invalid_argument(path + ": a straightness run needs at least 3 readings");
    }
  }
  return in;
}

namespace {

// Each result's held-out accuracy from k-fold cross-validation; with every pose in the fit,
// the only held-out figure there is.
std::string CrossValidatedLines(const ValidationReport& report) {
  std::string lines;
  for (const ModelValidation& v : report.models) {
    if (!v.cross_validation) continue;
    const CrossValidationFigures& cv = *v.cross_validation;
    lines += fmt::format("  {:<10} {}: {:.4f} mm, {:.4f} deg\n", v.label, CrossValidatedLabel(cv),
                         cv.position_rms_m * 1e3, DegreesFromRadians(cv.rotation_rms_rad));
  }
  return lines.empty() ? ""
                       : "Board pose error, each pose predicted by the fit without it:\n" + lines;
}

// Simulation: where the true robot goes through each identified model, beside what its
// result predicted (the figure to judge a calibration by, measured against the truth).
std::string TrueAccuracyLines(const ValidationReport& report) {
  std::string t;
  for (const auto& v : report.models) {
    if (!v.true_accuracy) continue;
    if (t.empty()) {
      t = "True robot accuracy (simulation: each of the 81 grid poses commanded through the "
          "model, reached by the true robot, base frame registered):\n";
    }
    const TrueAccuracy& a = *v.true_accuracy;
    t += fmt::format("  {:<10} RMS {:.4f} mm, max {:.4f} mm, Z scale {:+.0f} ppm over {} poses\n",
                     v.label, 1e3 * a.position_rms_m, 1e3 * a.position_max_m, a.z_scale_ppm,
                     a.poses);
  }
  return t;
}

}  // namespace

std::string FormatValidationText(const ValidationReport& report) {
  std::string t;
  // People read mm and deg (README.md#using-h4cal); the files keep m and rad.
  const auto deg = [](double rad) { return DegreesFromRadians(rad); };
  const std::string poses = EvaluatedPosesLabel(report);
  t += fmt::format("Table 3: joint residuals, {} (deg, measured - model)\n", poses);
  for (const auto& v : report.models) {
    const auto& r = v.heldout;
    t += fmt::format("  {:<10} mean {:9.4f} {:9.4f} {:9.4f} {:9.4f}\n", v.label, deg(r.mean[0]),
                     deg(r.mean[1]), deg(r.mean[2]), deg(r.mean[3]));
    t += fmt::format("  {:<10} RMS  {:9.4f} {:9.4f} {:9.4f} {:9.4f}\n", "", deg(r.rms[0]),
                     deg(r.rms[1]), deg(r.rms[2]), deg(r.rms[3]));
  }
  // Accuracy as RMS, 4 decimals of a mm: Model 31 results differ by hundredths.
  t += fmt::format("Positioning error (RMS): a priori, every pose: {:.4f} mm, {:.4f} deg\n",
                   report.apriori_all.position_rms * 1e3, deg(report.apriori_all.theta_rms));
  for (const auto& v : report.models) {
    t += fmt::format("  {:<10} {}: {:.4f} mm, {:.4f} deg\n", v.label, poses,
                     v.positioning.position_rms * 1e3, deg(v.positioning.theta_rms));
  }
  t += CrossValidatedLines(report);
  t += TrueAccuracyLines(report);
  if (!report.models.front().straightness.empty()) {
    t += "Table 4: straightness (mm, RMS distance to the fitted line)\n";
    for (size_t m = 0; m < report.models.size(); ++m) {
      t += fmt::format("  {:<10}", report.models[m].label);
      for (size_t r = 0; r < report.models[m].straightness.size(); ++r) {
        t += fmt::format("  dir {}: {:.4f}", r + 1,
                         1e3 * report.models[m].straightness[r].fit.rms_distance);
        if (m > 0) t += fmt::format(" ({:.0f} %)", report.StraightnessImprovementPercent(m, r));
      }
      t += "\n";
    }
  }
  for (const auto& v : report.models) {
    if (!v.square) continue;
    t += fmt::format(
        "Square, {} controller: side RMS {:.2f} {:.2f} {:.2f} {:.2f} mm, shape {:.2f} mm, "
        "mean |reached - commanded| {:.2f} mm\n",
        v.label, v.square->sides[0].rms * 1e3, v.square->sides[1].rms * 1e3,
        v.square->sides[2].rms * 1e3, v.square->sides[3].rms * 1e3, v.square->shape_rms * 1e3,
        v.square->mean_position_error * 1e3);
  }
  t += MeasuredSquareLines(report.measured_squares);
  for (const auto& v : report.models) {
    if (!v.accuracy_map) continue;
    t += fmt::format(
        "Accuracy map, {}: predicted 1-sigma position error median {:.4f} mm, largest {:.4f} "
        "mm over {} workspace poses\n",
        v.label, v.accuracy_map->MedianPositionSigma() * 1e3,
        v.accuracy_map->MaxPositionSigma() * 1e3, v.accuracy_map->points.size());
  }
  t += (report.prior.ok ? fmt::format("4-DoF check: rotation axis spread {:.3f} deg\n",
                                      report.prior.axis_spread_deg)
                        : "4-DoF check: " + report.prior.message + "\n");
  for (const auto& note : report.notes) fmt::format_to(std::back_inserter(t), "note: {}\n", note);
  return t;
}

}  // namespace h4::host::cli
