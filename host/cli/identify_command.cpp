// `h4cal identify`: Model 12 or Model 31 identification from a robot.yaml and a paired
// dataset (paper II-III; the solver is host/identification), writing the result JSON of
// common/formats/README.md. `--from result12.json` starts Model 31 from a Model 12 result (paper
// IV.C).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "common/board/board_model.h"
#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/corners_csv.h"
#include "common/formats/file_output.h"
#include "common/units.h"
#include "host/cli/calibration_workflow.h"
#include "host/cli/commands.h"
#include "host/cli/identification_print.h"
#include "host/cli/progress.h"
#include "host/cli/validation_inputs.h"
#include "host/formats/dataset_csv.h"
#include "host/formats/identification_result.h"
#include "host/formats/robot_yaml.h"
#include "host/identification/corner_checks.h"
#include "host/identification/corner_identification.h"
#include "host/identification/identification.h"
#include "host/identification/identified_robot.h"
#include "host/identification/verdict.h"
#include "host/validation/corner_residual_map.h"

namespace h4::host::cli {
namespace {

struct IdentifyCommandOptions {
  std::string robot_path;
  std::string data_path;
  std::string model = "12";  ///< the --model text, parsed in Run
  int validation = 0;
  // The library's defaults (IdentificationOptions), not restated here.
  int folds = IdentificationOptions{}.cross_validation.folds;
  bool validation_given = false;  ///< --validation on the command line (not the default)
  uint64_t seed = 1;
  std::string from_path;
  std::string out_path;
  std::string estimator = kCostKindNames.NameOf(IdentificationOptions{}.estimator);
  std::string algorithm = IdentificationOptions{}.nlopt.algorithm;
  std::vector<std::string> fix;
  bool no_outliers = false;
  bool no_polish = false;
  std::string report_dir;
  // The corner path (common/README.md#identification-from-corners).
  std::string corners_path;
  std::string board_path;
  std::string camera_path;
  bool camera_fixed = false;
  bool no_weigh_encoder_noise = false;  ///< CornerFitOptions::weigh_joint_noise off
  double default_sigma_px = 0.1;
  std::string camera_out_path;
};

// --validation draws held-out poses only from a dataset without a `set` column, and at
// most half of it (SplitDataset): asking for more is an error, not a silent cap. The
// split must leave calibration poses (a header-only file, a `set` column of only
// `valid`, the validation output of `h4cal simulate`).
void RequireUsableSplit(const IdentifyCommandOptions& options,
                        const std::vector<DatasetRow>& rows) {
  // With --from the split is the Model 12 result's; the identification checks that one.
  if (!options.from_path.empty()) return;
  const size_t calib = SplitDataset(rows, options.validation, options.seed).calib.size();
  if (calib < kMinimumCalibrationPoses) {
    throw std::invalid_argument(
        fmt::format("{}: identification needs at least {} calibration poses, the file has {} (of "
                    "{} rows; rows with set 'valid' are held out)",
                    options.data_path, kMinimumCalibrationPoses, calib, rows.size()));
  }
  const bool has_set =
      std::any_of(rows.begin(), rows.end(), [](const DatasetRow& r) { return r.set.has_value(); });
  const size_t most = rows.size() / 2;
  if (options.validation_given && !has_set && static_cast<size_t>(options.validation) > most) {
    throw std::invalid_argument(
        fmt::format("--validation {}: at most half of the {} poses of {} can be held out ({})",
                    options.validation, rows.size(), options.data_path, most));
  }
}

// The files a result came from, as given on the command line (its provenance).
std::vector<std::string> InputsOf(const IdentifyCommandOptions& options) {
  std::vector<std::string> inputs{options.robot_path, options.data_path};
  if (!options.from_path.empty()) inputs.push_back(options.from_path);
  return inputs;
}

// The corner path's account: what the camera became, beside the file's values.
void PrintCornerFit(const CornerPathOutcome& path) {
  const CornerFitOutcome& fit = path.fit;
  fmt::print("corner path: {}\n", fit.message);
  if (!path.outcome.result.camera) return;
  for (const ResultCameraParameter& p : path.outcome.result.camera->parameters) {
    if (p.std) {
      fmt::print("  {:<10} {:>14.8g} (file {:.8g}, change {:+.3g} = {:.1f} sigma), sigma {:.3g}\n",
                 p.name, p.value, p.file_value, p.value - p.file_value,
                 *p.std > 0 ? (p.value - p.file_value) / *p.std : 0.0, *p.std);
    } else {
      fmt::print("  {:<10} {:>14.8g} kept: {}\n", p.name, p.value, p.fixed_reason);
    }
  }
  if (!path.dropped.empty()) {
    fmt::print("  {} pose(s) without enough corners left out\n", path.dropped.size());
  }
}

// Which files go together, said before any work: the corner path needs its three; the
// camera file with its board alone gives the pose path the file's uncertainty.
void RequireCameraFiles(const IdentifyCommandOptions& options) {
  const bool corner_only =
      options.camera_fixed || options.no_weigh_encoder_noise || !options.camera_out_path.empty();
  if (options.corners_path.empty() && corner_only) {
    throw std::invalid_argument(
        "--camera-fixed, --no-weigh-encoder-noise and --camera-out belong to the corner path: give "
        "--corners, --board and --camera");
  }
  if (!options.corners_path.empty() &&
      (options.board_path.empty() || options.camera_path.empty())) {
    throw std::invalid_argument(
        "the corner path needs --corners, --board and --camera together (the corners CSV "
        "h4cal collect or h4cam measure --corners-out wrote, the board and the camera file "
        "h4cam used)");
  }
  if (options.board_path.empty() != options.camera_path.empty()) {
    throw std::invalid_argument(
        "--camera and --board go together: the camera file h4cam measured with and its board "
        "(without --corners, the pose path's covariance then carries the file's "
        "intrinsics_covariance)");
  }
}

// The camera file's uncertainty for the pose path (common/README.md#the-camera-files-uncertainty),
// when --camera and --board are given.
std::optional<CameraFileUncertainty> CameraFileOf(const IdentifyCommandOptions& options) {
  if (options.camera_path.empty()) return std::nullopt;
  CameraFileUncertainty file{ReadCameraYaml(options.camera_path),
                             BoardModel(ReadBoardYaml(options.board_path)).corners()};
  if (!file.camera.intrinsics_covariance && options.corners_path.empty()) {
    spdlog::warn(
        "{} has no intrinsics_covariance (h4cam calibrate-intrinsics writes one): the "
        "predicted accuracy assumes the intrinsics exact",
        options.camera_path);
  }
  return file;
}

int RunCornerPath(const IdentifyCommandOptions& options, const RobotDescription& robot,
                  ModelKind model, const std::vector<DatasetRow>& rows,
                  const IdentificationOutcome& pose_path, const IdentificationOptions& id_options,
                  const std::string& command_line);

void RequireValidInputs(const IdentifyCommandOptions& options) {
  std::string algorithm_why;
  if (!IsValidNloptAlgorithm(options.algorithm, &algorithm_why)) {
    throw std::invalid_argument("--algorithm: " + algorithm_why);
  }
  RequireCameraFiles(options);
  const std::vector<NamedPath> input_files = {
      {"--robot", options.robot_path}, {"--data", options.data_path},
      {"--from", options.from_path},   {"--corners", options.corners_path},
      {"--board", options.board_path}, {"--camera", options.camera_path}};
  RequireOutputIsNotAnInput({"--out", options.out_path}, input_files);
  if (!options.camera_out_path.empty()) {
    RequireOutputIsNotAnInput({"--camera-out", options.camera_out_path}, input_files);
  }
}

/// The library's options from the command's; `progress` shows each iteration.
IdentificationOptions IdentificationOptionsOf(const IdentifyCommandOptions& options,
                                              Progress* progress) {
  IdentificationOptions id_options;
  id_options.estimator = *ParseCostKind(options.estimator);  // CLI11 checked the name
  id_options.nlopt.algorithm = options.algorithm;
  id_options.fixed_parameters = options.fix;
  id_options.reject_outliers = !options.no_outliers;
  id_options.lm_polish = !options.no_polish;
  id_options.cross_validation.folds = options.folds;
  id_options.cross_validation.seed = options.seed;
  id_options.camera_file = CameraFileOf(options);
  if (!options.board_path.empty())
    id_options.board_size_sigma = BoardSizeSigma(ReadBoardYaml(options.board_path));
  // One count however often the library copies the options (cross-validation does).
  id_options.progress = [progress, iterations = std::make_shared<int>(0)](
                            const std::string& stage, int iteration, double cost) {
    progress->Update(++*iterations, fmt::format("{} it {} cost {:.4g}", stage, iteration, cost));
    return true;
  };
  std::string why;
  if (!id_options.IsValid(&why)) throw std::invalid_argument(why);
  return id_options;
}

/// Model 12 or 31 from the a priori robot, or Model 31 from a Model 12 result (--from).
IdentificationOutcome IdentifyAsAsked(const IdentifyCommandOptions& options,
                                      const RobotDescription& robot, ModelKind model,
                                      const std::vector<DatasetRow>& rows,
                                      const IdentificationOptions& id_options) {
  if (options.from_path.empty()) {
    return IdentifyRobot(robot, model, rows, id_options, options.validation, options.seed);
  }
  if (model != ModelKind::k31) {
    throw std::invalid_argument("--from starts a Model 31 identification: use it with --model 31");
  }
  const IdentificationResult from = ReadIdentificationResult(options.from_path);
  RequireModel12Result(from, options.from_path, "--from");
  return IdentifyModel31FromModel12(robot, from, rows, id_options);
}

/// A Model 31 the corners say cannot describe the robot: the advice the corner residuals'
/// pattern over the image gives (the lens, the focal length, or the robot and mounts)
/// replaces the board-pose advice, which can only name the robot (issue 43 point 7).
void AdviseFromCornerPattern(const Assembly& assembly, const std::vector<DatasetRow>& rows,
                             const std::vector<CornerObservation>& observed,
                             const BoardModel& board, const CameraIntrinsics& camera,
                             IdentificationOutcome* outcome) {
  std::optional<ResultVerdict>& verdict = outcome->result.verdict;
  if (outcome->verdict != Verdict::kModelCannotDescribe || !verdict) return;
  const size_t at = verdict->text.find(kModel31MisfitAdvice);
  if (at == std::string::npos) return;
  std::string advice;
  try {
    advice = CornerResidualPatternAdvice(
        ComputeCornerResidualMap(outcome->result, assembly, rows, observed, board, camera));
  } catch (const std::invalid_argument& e) {  // no map (e.g. corners far off the board)
    spdlog::warn("no corner residual pattern to advise from: {}", e.what());
    return;
  }
  verdict->text.replace(at, std::string(kModel31MisfitAdvice).size(), advice);
}

/// The report of this result: validation on its held-out poses, with the Model 12 result
/// it started from when there is one.
void WriteReport(const IdentifyCommandOptions& options, ModelKind model,
                 const std::string& command_line) {
  ValidationFileOptions files;
  files.robot_path = options.robot_path;
  files.data_path = options.data_path;
  (model == ModelKind::k12 ? files.result12_path : files.result31_path) = options.out_path;
  if (!options.from_path.empty()) files.result12_path = options.from_path;
  const ValidationReport report = ValidateAndReport(files, options.report_dir, command_line, false);
  PrintAccuracyMapLine(report.models.back());
}

int Run(const IdentifyCommandOptions& options, const std::string& command_line) {
  RequireValidInputs(options);
  const RobotDescription robot = ReadRobotYaml(options.robot_path);
  const std::vector<DatasetRow> rows = ReadDatasetCsv(options.data_path);
  RequireUsableSplit(options, rows);
  Progress progress("identify Model " + options.model, 0);
  const IdentificationOptions id_options = IdentificationOptionsOf(options, &progress);
  const ModelKind model = *ParseModelKind(options.model);  // CLI11 checked the text
  const IdentificationOutcome outcome = IdentifyAsAsked(options, robot, model, rows, id_options);
  progress.Finish(outcome.summary.message);
  if (!options.corners_path.empty()) {
    return RunCornerPath(options, robot, model, rows, outcome, id_options, command_line);
  }
  // The verdict first: a result its reader would refuse is not written (the write throws),
  // and the verdict still says what went wrong.
  spdlog::debug("{}", outcome.summary.FullReport());
  PrintHeadline(outcome);
  WriteResultWithProvenance(options.out_path, outcome.result, InputsOf(options));
  spdlog::info("result written to {}", options.out_path);
  if (!outcome.summary.usable) {
    spdlog::error("the identification is not usable: {}", outcome.summary.message);
    if (!options.report_dir.empty()) spdlog::error("no report written for an unusable result");
    return h4::cli::kExitNothingUsable;
  }
  if (!options.report_dir.empty()) WriteReport(options, model, command_line);
  return outcome.verdict == Verdict::kGood ? h4::cli::kExitSuccess : h4::cli::kExitNothingUsable;
}

int RunCornerPath(const IdentifyCommandOptions& options, const RobotDescription& robot,
                  ModelKind model, const std::vector<DatasetRow>& rows,
                  const IdentificationOutcome& pose_path, const IdentificationOptions& id_options,
                  const std::string& command_line) {
  if (!pose_path.summary.usable) {
    PrintHeadline(pose_path);
    throw std::runtime_error("the pose path, the corner path's start, is not usable: " +
                             pose_path.summary.message);
  }
  const BoardModel board(ReadBoardYaml(options.board_path));
  const CameraIntrinsics camera = ReadCameraYaml(options.camera_path);
  const std::vector<CornerObservation> observed = ReadCornersCsv(options.corners_path);
  RequireCornersOfDataset(rows, observed, options.corners_path);
  RequireCornersInImage(rows, observed, camera);
  std::vector<PoseCorners> corners =
      GroupCornersByRow(rows, observed, board, options.default_sigma_px);
  for (const std::string& why : DropDegenerateCornerPoses(rows, &corners)) {
    spdlog::warn("{}: {}", options.corners_path, why);
  }
  CornerFitOptions corner_options;
  corner_options.camera_fixed = options.camera_fixed;
  corner_options.weigh_joint_noise = !options.no_weigh_encoder_noise;
  CornerPathOutcome path = IdentifyOnCorners(AprioriModelOf(robot, model), model, pose_path, rows,
                                             corners, camera, id_options, corner_options);
  if (path.fit.ok && path.outcome.summary.usable) {
    FlagOverstatedCornerNoise(path.fit.uncertainty.chi2_per_dof, &path.outcome.verdict,
                              &path.outcome.result);
    AdviseFromCornerPattern(robot.assembly, path.rows, observed, board, camera, &path.outcome);
  }
  if (!path.fit.ok) {
    PrintCornerFit(path);
    throw std::runtime_error("the corner fit failed: " + path.fit.message);
  }
  // A refined camera the camera file's reader would refuse (a lens that folds inside the
  // image, a principal point off it) is not written: the result would not read back.
  if (const std::string problem = CameraIntrinsicsProblem(path.fit.camera); !problem.empty()) {
    PrintCornerFit(path);
    throw std::runtime_error("the corner fit's camera cannot be trusted: " + problem);
  }
  std::vector<std::string> inputs = InputsOf(options);
  inputs.insert(inputs.end(), {options.corners_path, options.board_path, options.camera_path});
  PrintHeadline(path.outcome);
  PrintCornerFit(path);
  WriteResultWithProvenance(options.out_path, path.outcome.result, inputs);
  if (!options.camera_out_path.empty()) {
    WriteCameraYaml(options.camera_out_path, path.fit.camera);
    spdlog::info("refined camera written to {}", options.camera_out_path);
  }
  spdlog::info("result written to {}", options.out_path);
  const int exit_code = path.outcome.verdict == Verdict::kGood && path.outcome.summary.usable
                            ? h4::cli::kExitSuccess
                            : h4::cli::kExitNothingUsable;
  if (options.report_dir.empty() || !path.outcome.summary.usable) return exit_code;
  // The report validates against the poses measured again with the refined camera, the
  // ones the result was fitted to; they are kept beside the report.
  std::filesystem::create_directories(options.report_dir);
  const std::string refit_path = options.report_dir + "/dataset_from_corners.csv";
  WriteDatasetCsv(refit_path, path.rows);
  ValidationFileOptions files;
  files.robot_path = options.robot_path;
  files.data_path = refit_path;
  (model == ModelKind::k12 ? files.result12_path : files.result31_path) = options.out_path;
  // The Model 12 result it started from, as the pose path's report has it: the a priori row
  // then uses the same identified placement, and both reports give the same a priori error.
  if (!options.from_path.empty()) files.result12_path = options.from_path;
  files.corners_path = options.corners_path;  // the camera section's residual map
  files.board_path = options.board_path;
  files.camera_path = options.camera_path;
  const ValidationReport report = ValidateAndReport(files, options.report_dir, command_line, false);
  PrintAccuracyMapLine(report.models.back());
  return exit_code;
}

}  // namespace

void DeclareIdentifyCommand(CLI::App* command) {
  const auto options = std::make_shared<IdentifyCommandOptions>();
  h4::cli::AddRobotOption(command, &options->robot_path)->required();
  h4::cli::AddDataOption(command, &options->data_path)->required();
  h4::cli::AddModelOption(command, &options->model, "Kinematic model");
  h4::cli::AddOptionShowingDefault(
      command, "--validation", &options->validation,
      "Poses held out of the fit (the paper's fixed split) when the dataset has no "
      "'set' column; 0: every pose in the fit, held-out figures by cross-validation",
      CLI::NonNegativeNumber);
  h4::cli::AddSeedOption(command, &options->seed, "Seed of that split and of the folds");
  h4::cli::AddOptionShowingDefault(
      command, "--folds", &options->folds,
      "k of the k-fold cross-validation giving the held-out figures and judging "
      "outliers (each pose predicted by a fit without it); 0: off",
      CLI::NonNegativeNumber);
  h4::cli::AddInputFileOption(command, "--from", &options->from_path,
                              "Model 12 result to start Model 31 from; parameters Model 31 must "
                              "fix take its values (paper IV.C)");
  h4::cli::AddChoiceOption(command, "--estimator", &options->estimator, kCostKindNames,
                           "Cost: measurement (6-DoF board pose, weighted; default), joint (the "
                           "paper's eq. (3)), implicit (eq. (5))")
      ->capture_default_str();
  std::string algorithms;
  for (const std::string& name : NloptAlgorithmNames()) algorithms += " " + name;
  command
      ->add_option("--algorithm", options->algorithm,
                   "NLopt algorithm of every stage, before the Levenberg-Marquardt polish; one "
                   "of" +
                       algorithms + ", or none (LM alone)")
      ->capture_default_str();
  command->add_option("--fix", options->fix, "Parameters to keep at their a priori value")
      ->delimiter(',');
  command->add_flag("--no-outlier-rejection", options->no_outliers, "Keep every pose");
  command->add_flag("--no-polish", options->no_polish,
                    "Skip the Levenberg-Marquardt polish: NLopt alone, run to tight tolerances");
  h4::cli::AddInputFileOption(command, "--corners", &options->corners_path,
                              "Corner path: the board corners of every pose (CSV, "
                              "common/formats/README.md); fits in pixels with the camera's "
                              "intrinsics refined with the robot (needs --board, --camera)");
  h4::cli::AddBoardOption(command, &options->board_path)
      ->description("The board YAML the poses (and corners) were measured on (with --camera)");
  h4::cli::AddCameraOption(command, &options->camera_path,
                           "The camera file h4cam used (with --board): its "
                           "intrinsics_covariance enters the pose path's covariance; with "
                           "--corners, its intrinsics are refined");
  command->add_flag("--camera-fixed", options->camera_fixed,
                    "Corner path: keep every intrinsic at the camera file's value");
  command->add_flag("--no-weigh-encoder-noise", options->no_weigh_encoder_noise,
                    "Corner path: weigh every corner as an independent look at the robot instead "
                    "of each pose's corners by the encoder noise they show (generalised least "
                    "squares, the default; common/README.md#identification-from-corners)");
  h4::cli::AddOptionShowingDefault(
      command, "--corner-sigma", &options->default_sigma_px,
      "Corner path: per-axis corner sigma (px) of corners without a sigma_px column",
      CLI::Range(1e-6, 100.0));
  command->add_option("--camera-out", options->camera_out_path,
                      "Corner path: write the refined camera as a camera YAML");
  h4::cli::AddOutOption(command, &options->out_path, "Result JSON");
  h4::cli::AddReportDirOption(command, &options->report_dir)
      ->description("Also validate on the held-out poses and write DIR/report.html");
  command->footer(
      "Exit code 3: the result was written but its verdict is not 'good' (printed first, and "
      "in the result's 'verdict' key).");
  RunWithCommandLineWhenParsed(
      command, options, [command](IdentifyCommandOptions& parsed, const std::string& command_line) {
        parsed.validation_given = command->count("--validation") > 0;
        return Run(parsed, command_line);
      });
}

}  // namespace h4::host::cli
