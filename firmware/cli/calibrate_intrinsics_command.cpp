// `h4cam calibrate-intrinsics`; see calibrate_intrinsics_command.h.
#include "firmware/cli/calibrate_intrinsics_command.h"

#include <filesystem>
#include <map>
#include <memory>
#include <ostream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/board/board_model.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "common/formats/file_output.h"
#include "firmware/calibration/intrinsics_report.h"
#include "firmware/sources/image_file_source.h"

namespace h4::cam {
namespace {

namespace fs = std::filesystem;

/// What was found of the board: "chessboard: 54/54 corners", or on an AprilTag grid
/// "30/36 tags, 120/144 corners" (every tag found gives its 4 corners, board_views.h).
std::string BoardFound(const CalibrationView& view, const BoardModel& board) {
  const std::string corners =
      fmt::format("{}/{} corners", view.image_points.size(), board.corner_count());
  if (!board.is_aprilgrid()) return "chessboard: " + corners;
  const auto& grid = std::get<AprilGridSpec>(board.spec());
  return fmt::format("{}/{} tags, {}", view.image_points.size() / 4, grid.rows * grid.cols,
                     corners);
}

/// The report's files beside the camera YAML, named after it: camera.yaml ->
/// camera-report.html, camera-coverage.svg, camera-residuals.svg, camera-report.txt.
struct ReportPaths {
  fs::path html, coverage_svg, residuals_svg, text;
};

ReportPaths ReportPathsBeside(const std::string& camera_yaml) {
  const fs::path yaml(camera_yaml);
  const fs::path stem = yaml.parent_path() / yaml.stem();
  const auto named = [&](const char* suffix) { return fs::path(stem.string() + suffix); };
  return {named("-report.html"), named("-coverage.svg"), named("-residuals.svg"),
          named("-report.txt")};
}

/// Writes the report (intrinsics_report.h) beside the camera YAML, each file atomically;
/// prints the coverage and the files written.
void WriteReportFiles(const IntrinsicsCalibrationResult& result, const std::string& camera_yaml,
                      std::ostream& out) {
  const ReportPaths paths = ReportPathsBeside(camera_yaml);
  const CoverageGrid grid = CornerCoverage(result);
  const ReportFiles names = {
      fs::path(camera_yaml).filename().string(), paths.coverage_svg.filename().string(),
      paths.residuals_svg.filename().string(), paths.text.filename().string()};
  WriteFileAtomically(paths.coverage_svg.string(), CoverageSvg(result, grid));
  WriteFileAtomically(paths.residuals_svg.string(), ResidualsSvg(result));
  WriteFileAtomically(paths.text.string(), result.Report() + CoverageSummary(grid) + "\n");
  WriteFileAtomically(paths.html.string(), ReportHtml(result, grid, names));
  out << "coverage: " << CoverageSummary(grid) << "\n"
      << "report: " << paths.html.string() << " (with " << paths.coverage_svg.string() << ", "
      << paths.residuals_svg.string() << ", " << paths.text.string() << ")\n";
}

}  // namespace

IntrinsicsCalibrationResult RunCalibrateIntrinsics(const CalibrateIntrinsicsArgs& args,
                                                   std::ostream& out) {
  // Before the calibration, not after it (issue 42): the folder the files go to.
  RequireOutputFolder({"--out", args.out_path});
  const BoardSpec board = ReadBoardYaml(args.board_path);
  const BoardModel board_model(board);
  const BoardViewFinder finder(board);
  if (!finder.ok()) throw std::runtime_error(args.board_path + ": " + finder.error());

  std::vector<CalibrationView> views;
  cv::Size image_size;
  for (const auto& path : args.images) {
    // The image reader every h4cam command uses: a regular file, its header's size within
    // the limits before anything is decoded (a 32000 x 32000 PNG took 3.6 GB, issue 42).
    std::string read_why;
    const cv::Mat grey = ImageFileSource::ReadGrey(path, &read_why);
    if (grey.empty()) throw std::runtime_error(read_why);
    if (image_size.empty()) image_size = grey.size();
    if (grey.size() != image_size) {
      throw std::runtime_error(fmt::format("{}: image is {}x{}, expected {}x{} like {}", path,
                                           grey.cols, grey.rows, image_size.width,
                                           image_size.height, args.images[0]));
    }
    std::string why;
    if (auto view = finder.Find(grey, path, &why)) {
      out << path << ": board found, " << BoardFound(*view, board_model) << "\n";
      views.push_back(std::move(*view));
    } else {
      out << path << ": skipped: " << why << "\n";
    }
  }

  IntrinsicsCalibrationResult result = CalibrateIntrinsics(views, image_size, args.options);
  out << result.Report();
  if (!result.ok()) throw std::runtime_error("calibrate-intrinsics: " + result.message);
  WriteCameraYaml(args.out_path, result.camera);
  out << "wrote " << args.out_path << "\n";
  WriteReportFiles(result, args.out_path, out);
  return result;
}

void DeclareCalibrateIntrinsicsCommand(CLI::App* command) {
  const auto args = std::make_shared<CalibrateIntrinsicsArgs>();
  h4::cli::AddBoardOption(command, &args->board_path)->required();
  command->add_option("images", args->images, "Images of the board (at least --min-views)")
      ->required()
      ->check(CLI::ExistingFile);
  h4::cli::AddOutOption(command, &args->out_path,
                        "Camera YAML to write; the report goes beside it, named after it "
                        "(camera.yaml: camera-report.html with camera-coverage.svg, "
                        "camera-residuals.svg, camera-report.txt)");
  const std::map<std::string, IntrinsicsModel> models = {
      {"radtan", IntrinsicsModel::kRadTan},
      {"rational", IntrinsicsModel::kRational},
      {"equidistant", IntrinsicsModel::kEquidistant}};
  command
      // The camera file's key; --model is identify's and plan's kinematic model.
      ->add_option("--distortion-model,--model", args->options.model,
                   "Lens model: radtan (k1 k2 p1 p2 k3), rational (8 coefficients, "
                   "CALIB_RATIONAL_MODEL) or equidistant (fisheye k1..k4, cv::fisheye)")
      ->transform(CLI::CheckedTransformer(models))
      ->default_str("radtan");
  command->add_flag("--fix-aspect-ratio", args->options.fix_aspect_ratio, "Calibrate with fx = fy");
  command->add_flag("--hold-k3", args->options.hold_k3,
                    "Hold k3 at 0 (radtan, rational); radtan does so by itself when k3 folds "
                    "the lens model inside the image");
  command
      ->add_option("--min-views", args->options.min_views,
                   "Fewest images with the board to calibrate from")
      ->default_val(args->options.min_views);
  command
      ->add_option("--outlier-factor", args->options.outlier_factor,
                   "A view whose RMS error exceeds this x the median is an outlier")
      ->default_val(args->options.outlier_factor);
  command->add_flag("--drop-outliers", args->options.drop_outliers,
                    "Drop the outlier views and calibrate again");
  h4::cli::RunWhenParsed(command, args, [](const CalibrateIntrinsicsArgs& parsed) {
    RunCalibrateIntrinsics(parsed, std::cout);
  });
}

}  // namespace h4::cam
