// The camera study (issue 25; docs/results.md#when-the-camera-file-is-wrong-the-corner-path): how
// wrong a camera file may be before the robot pays for it, and what the corner path recovers. For
// each simulated Model 31 robot and each camera-file error, the campaign is simulated with the TRUE
// camera of boards/sim_camera_1024x768.yaml (the legacy 6x6 board's 144 corners, per-axis pixel
// noise, encoder noise), board poses solved with the FILE's intrinsics; then the pose path
// (Model 12, then Model 31 --from) and the corner path (from that Model 31) are identified
// and each result's TRUE registered accuracy measured where the true robot goes over the
// paper's 81 grid poses (host/validation/true_accuracy.h).
// The camera files: the true one with a stated error, a draw from a 25-view chessboard
// calibration's covariance, and a real calibration (h4cam calibrate-intrinsics) from 25
// rendered views (host/bench/calibrated_camera_file.sh). With --plan, the campaigns use a
// poses CSV (`h4cal plan`) instead of the grid: how well the robot's motion determines the
// intrinsics (the sigma columns) depends on the poses.
//   h4_camera_study [--robots N] [--first-seed S] [--prior simulate|wide] [--sigma-px P]
//                 [--sigma-q RAD] [--plan POSES.csv]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "common/board/board_model.h"
#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/bench/study_main.h"
#include "host/formats/pose_plan_rows.h"
#include "host/formats/poses_csv.h"
#include "host/identification/corner_identification.h"
#include "host/identification/identification.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/calibration_draw.h"
#include "host/simulation/corner_campaign.h"
#include "host/validation/true_accuracy.h"

namespace h4::host {
namespace {

struct StudyOptions {
  int robots = 3;
  uint64_t first_seed = 1;
  bool wide_prior = false;
  double sigma_px = 0.05;
  double sigma_q = 2e-5;  // encoder noise, rad
  std::string plan_path;  // poses CSV of the campaigns; empty: the paper's grid
};

struct CameraError {
  const char* name;
  double fx = 0, fy = 0;       // relative
  double cx = 0, cy = 0;       // px
  double k1 = 0;               // relative
  bool drawn = false;          // a draw from the 25-view calibration's covariance instead
  const char* file = nullptr;  // a camera file of boards/ instead, with its own covariance
};

const std::vector<CameraError>& CameraErrors() {
  static const std::vector<CameraError> kErrors = {
      {"exact"},
      {"focal +0.1 %", 1e-3, 1e-3},
      {"focal +0.3 %", 3e-3, 3e-3},
      {"cx +1 px, cy -1 px", 0, 0, 1.0, -1.0},
      {"k1 +2 %", 0, 0, 0, 0, 0.02},
      // fx +0.15 %, fy +0.12 %, cx +0.7 px, cy -0.5 px, k1 +1 %, claiming a looser
      // calibration than the draws' (its error about one sigma).
      {"typical mix", 0, 0, 0, 0, 0, false, "sim_camera_1024x768_typical_error.yaml"},
      {"25-view calibration", 0, 0, 0, 0, 0, true},
      {"25 rendered views", 0, 0, 0, 0, 0, false, "sim_camera_1024x768_calibrated_25_views.yaml"},
  };
  return kErrors;
}

CameraIntrinsics WithError(CameraIntrinsics c, const CameraError& e) {
  c.K(0, 0) *= 1 + e.fx;
  c.K(1, 1) *= 1 + e.fy;
  c.K(0, 2) += e.cx;
  c.K(1, 2) += e.cy;
  c.distortion[0] *= 1 + e.k1;
  return c;
}

// --prior wide: deviations several times simulate's (centimetres and degrees of camera
// set-up, millimetres of geometry), a robot the project's generator would rarely draw.
PerturbationOptions Prior(const StudyOptions& options, uint64_t seed) {
  PerturbationOptions p{.seed = seed};
  if (options.wide_prior) {
    p.length_std = 0.005;
    p.angle_std = 0.04;
    p.base_joint_std = 0.006;
    p.camera_translation_std = 0.05;
    p.camera_rotation_std = 0.08;
  }
  return p;
}

// Per camera-file error: the sum of log(true RMS / the exact camera's pose-path RMS) over
// the robots, for the pose path and the corner path, and the count.
struct RatioTally {
  double log_pose = 0, log_corner = 0;
  int robots = 0;
};
std::vector<RatioTally> g_tally;
double g_exact_pose_rms = 0;

PosePlan CampaignPlan(const StudyOptions& options) {
  if (options.plan_path.empty()) return GridPosePlan();
  static const PosePlan plan = PosePlanFromRows(ReadPosesCsv(options.plan_path));
  return plan;
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void RunOne(const SimulatedRobot& truth, const CameraError& error, uint64_t seed,
            const StudyOptions& options) {
  const std::string dir = std::string(H4_SOURCE_DIR) + "/boards/";
  const CameraIntrinsics true_camera = ReadCameraYaml(dir + "sim_camera_1024x768.yaml");
  static const Eigen::MatrixXd calibration = ChessboardCalibrationCovariance(true_camera);
  CameraIntrinsics file_camera = true_camera;
  if (error.file != nullptr) {
    file_camera = ReadCameraYaml(dir + error.file);
  } else {
    file_camera = error.drawn ? DrawnFromCovariance(true_camera, calibration, 1000 + seed)
                              : WithError(true_camera, error);
    file_camera.intrinsics_covariance = calibration;
  }
  const BoardModel board(ReadBoardYaml(dir + "aprilgrid_6x6_30mm.yaml"));
  const CornerCampaign campaign = SimulateCornerCampaign(
      truth, CampaignPlan(options), board, true_camera, file_camera,
      {.sigma_px = options.sigma_px, .sigma_q = options.sigma_q, .seed = seed});
  const RobotDescription apriori = PaperAprioriRobot();
  std::vector<EePose> grid;
  for (const PlannedPose& p : GridPosePlan()) grid.push_back(p.x);
  IdentificationOptions id_options;
  // The pose path knows the file's covariance: its predicted accuracy carries it.
  id_options.camera_file = CameraFileUncertainty{file_camera, board.corners()};
  const IdentificationOutcome m31 =
      IdentifyModel12Then31(apriori, campaign.rows, id_options).model31;
  const TrueAccuracy pose = TrueAccuracyOfResult(m31.result, truth, grid);
  // A pose path that fails (a start the fit cannot leave, `inconsistent_with_apriori`) is no
  // start for the corner path: the row is named and left out of the means (the whole robot
  // when it is the exact camera's, whose RMS the ratios divide by).
  const bool wrong_start =
      m31.result.verdict && m31.result.verdict->code == "inconsistent_with_apriori";
  if (!m31.summary.usable || wrong_start || !(pose.position_rms_m > 0)) {
    fmt::print("| {:<20} | {} | not usable: left out of the means | | | | | | | | |\n", error.name,
               m31.result.verdict ? m31.result.verdict->code.c_str() : "-");
    return;
  }
  const double start = CpuSeconds();
  const CornerPathOutcome path =
      IdentifyOnCorners(AprioriModelOf(apriori, ModelKind::k31), ModelKind::k31, m31, campaign.rows,
                        GroupCornersByRow(campaign.rows, campaign.corners, board, options.sigma_px),
                        file_camera, id_options, {});
  const double cpu = CpuSeconds() - start;
  const TrueAccuracy corner = TrueAccuracyOfResult(path.outcome.result, truth, grid);
  const auto sigma = [&](size_t k) {
    const ResultCamera& c = *path.outcome.result.camera;
    return k < c.parameters.size() && c.parameters[k].std ? *c.parameters[k].std : NAN;
  };
  if (&error == &CameraErrors().front()) g_exact_pose_rms = pose.position_rms_m;
  if (!(g_exact_pose_rms > 0)) return;  // the exact camera's pose path failed on this robot
  RatioTally& tally = g_tally[static_cast<size_t>(&error - &CameraErrors().front())];
  tally.log_pose += std::log(pose.position_rms_m / g_exact_pose_rms);
  tally.log_corner += std::log(corner.position_rms_m / g_exact_pose_rms);
  ++tally.robots;
  const double pose_pred = m31.result.predicted_robot_accuracy_m.value_or(NAN);
  const double corner_pred = path.outcome.result.predicted_robot_accuracy_m.value_or(NAN);
  fmt::print(
      "| {:<20} | {} | {:.4f} ({:>+6.0f} ppm) | {:.4f} | {:.4f} ({:>+6.0f} ppm) | {:.4f} | {:.0f} "
      "ppm | {:.3f} px | {:.3f} % | {:.1f} urad | {:.2f} s |\n",
      error.name, m31.result.verdict ? m31.result.verdict->code.c_str() : "-",
      1e3 * pose.position_rms_m, pose.z_scale_ppm, 1e3 * pose_pred, 1e3 * corner.position_rms_m,
      corner.z_scale_ppm, 1e3 * corner_pred, 1e6 * sigma(0) / true_camera.K(0, 0), sigma(2),
      100 * sigma(4) / std::abs(true_camera.distortion[0]), 1e6 * path.fit.joint_noise.sigma_q,
      cpu);
  std::fflush(stdout);
}

void Run(const StudyOptions& options) {
  g_tally.assign(CameraErrors().size(), RatioTally{});
  {
    const CameraIntrinsics camera =
        ReadCameraYaml(std::string(H4_SOURCE_DIR) + "/boards/sim_camera_1024x768.yaml");
    const Eigen::VectorXd sigma = ChessboardCalibrationCovariance(camera).diagonal().cwiseSqrt();
    fmt::print(
        "the stated errors and the draws carry a 25-view chessboard calibration's covariance "
        "(the "
        "files their own): sigma fx {:.0f} "
        "ppm, fy {:.0f} ppm, cx {:.2f} px, cy {:.2f} px, k1 {:.2f} %\n",
        1e6 * sigma[0] / camera.K(0, 0), 1e6 * sigma[1] / camera.K(1, 1), sigma[2], sigma[3],
        100 * sigma[4] / std::abs(camera.distortion[0]));
  }
  fmt::print(
      "prior {}, corner noise {:.3g} px, encoder noise {:.3g} rad, {} ({} poses), legacy 6x6 "
      "board\n\n"
      "| camera file error | pose-path verdict | pose path TRUE RMS mm (Z scale) | pose path "
      "predicted mm | corner path TRUE RMS mm (Z scale) | corner path predicted mm | sigma fx | "
      "sigma cx | sigma k1 | joint noise seen | corner path CPU |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n",
      options.wide_prior ? "wide" : "simulate", options.sigma_px, options.sigma_q,
      options.plan_path.empty() ? "paper grid" : options.plan_path.c_str(),
      CampaignPlan(options).size());
  for (int r = 0; r < options.robots; ++r) {
    const uint64_t seed = options.first_seed + static_cast<uint64_t>(r);
    const SimulatedRobot truth =
        MakeTrueRobot(PaperAprioriRobot(), TrueGeometry::kPerturbedModel31, Prior(options, seed));
    fmt::print("| **robot {}** | | | | | | | | | | |\n", static_cast<unsigned long long>(seed));
    g_exact_pose_rms = 0;
    for (const CameraError& error : CameraErrors()) RunOne(truth, error, seed, options);
  }
  fmt::print(
      "\nGeometric mean over the robots of TRUE RMS / the exact camera's pose-path RMS:\n\n"
      "| camera file error | pose path | corner path |\n|---|---|---|\n");
  for (size_t k = 0; k < CameraErrors().size(); ++k) {
    const RatioTally& t = g_tally[k];
    fmt::print("| {} | {:.2f} | {:.2f} |\n", CameraErrors()[k].name,
               std::exp(t.log_pose / t.robots), std::exp(t.log_corner / t.robots));
  }
}

StudyOptions Parse(int argc, char** argv) {
  StudyOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--robots") {
      options.robots = std::stoi(value());
    } else if (arg == "--first-seed") {
      options.first_seed = std::stoull(value());
    } else if (arg == "--prior") {
      const std::string prior = value();
      if (prior != "simulate" && prior != "wide")
        throw std::invalid_argument("--prior simulate|wide");
      options.wide_prior = prior == "wide";
    } else if (arg == "--sigma-px") {
      options.sigma_px = std::stod(value());
    } else if (arg == "--sigma-q") {
      options.sigma_q = std::stod(value());
    } else if (arg == "--plan") {
      options.plan_path = value();
    } else {
      throw std::invalid_argument(
          "unknown option " + arg +
          " (--robots N --first-seed S --prior simulate|wide --sigma-px P --sigma-q RAD "
          "--plan POSES.csv)");
    }
  }
  if (options.robots < 1 || !(options.sigma_px > 0) || !(options.sigma_q >= 0))
    throw std::invalid_argument("bad option value");
  return options;
}

}  // namespace
}  // namespace h4::host

int main(int argc, char** argv) {
  return h4::host::StudyMain("h4_camera_study", argc, argv, h4::host::Parse, h4::host::Run);
}
