// Accuracy of the measuring pipeline under what a real camera's processed output does:
// blur, an unknown gamma-like response, an illumination gradient and shot noise
// (degraded_scene.h applied to BoardRenderer::RenderClean). Paper-like scenes (1024 x 768,
// ~817 px, 6 x 6 tags of 30 mm at 0.45-0.65 m, 10 frames averaged). Prints, per condition,
// the position and rotation error RMS and the reported sigma over the actual error, against
// the accuracy goals: <= 0.03 mm, <= 0.005 deg, sigma/actual within 0.5..2 (clean scenes
// <= 0.01 mm).
// Usage: h4_measure_response [scenes=12] [erosion=affine|global|tag|none] [seed=1]
//        [covariance=edge_noise|residual|group] [corner_floor_px=0.0015]
//        [inner_clearance_px=2.5] [inner_clearance_blur=0] [conditions=all|blur|TEXT]
//        [inner_edge=inner|clear] [band_px=2.5] [board=legacy|kalibr]
// (the clearances: the edge fit's dark-side clearance from the tag border's inner edge,
// edge_refinement.h; "blur" runs only the blur 1.4 rows, TEXT the rows whose name holds it).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "common/geometry/rotation.h"
#include "common/timing/clock.h"
#include "common/units.h"
#include "firmware/bench/bench_arguments.h"
#include "firmware/bench/degraded_scene.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"

namespace h4::cam {
namespace {

struct Condition {
  std::string name;
  double blur_px_min, blur_px_max;  // blur drawn uniformly per scene
  double gamma_min, gamma_max;      // response exponent drawn uniformly per scene
  double gradient;                  // +- illumination gain, random direction when > 0
  double read_noise, shot_noise;    // degraded_scene.h
};

std::vector<Condition> Conditions() {
  return {
      {"clean (blur 0.8, noise 2)", 0.8, 0.8, 1.0, 1.0, 0.0, 2.0, 0.0},
      {"blur 1.4", 1.4, 1.4, 1.0, 1.0, 0.0, 2.0, 0.0},
      {"blur 1.4, no noise (bias only)", 1.4, 1.4, 1.0, 1.0, 0.0, 0.0, 0.0},
      {"gamma 0.7, blur 0.7", 0.7, 0.7, 0.7, 0.7, 0.0, 2.0, 0.0},
      {"gamma 0.7, blur 1.4, grad 20%, shot", 1.4, 1.4, 0.7, 0.7, 0.2, 1.0, 0.03},
      {"gamma 0.45, blur 1.0", 1.0, 1.0, 0.45, 0.45, 0.0, 2.0, 0.0},
      {"random: blur .5-1.5, gamma .45-1, grad, shot", 0.5, 1.5, 0.45, 1.0, 0.2, 1.0, 0.03},
  };
}

struct Sums {
  double err_t2 = 0, err_r2 = 0, sig_t2 = 0, sig_r2 = 0, erosion_px = 0;
  int used = 0, failed = 0;
};

void MeasureScene(const MeasurePipeline& pipeline, const cv::Mat& mean, const RigidTransform& X_CT,
                  Sums* sums) {
  const Measurement m = pipeline.MeasureImage(mean, 10);
  if (!m.ok()) {
    ++sums->failed;
    return;
  }
  const Eigen::Vector3d e_t = m.X_CT.translation() - X_CT.translation();
  const Eigen::Vector3d e_r = So3Log(X_CT.rotation().transpose() * m.X_CT.rotation());
  sums->err_t2 += e_t.squaredNorm();
  sums->err_r2 += e_r.squaredNorm();
  sums->sig_t2 += 3 * m.sigma_t * m.sigma_t;  // sigma_t is per axis
  sums->sig_r2 += 3 * m.sigma_r * m.sigma_r;
  sums->erosion_px += m.erosion_px;
  ++sums->used;
}

// The arguments as key=value; a bare value takes the next of scenes, erosion, seed (the
// earlier positional form, docs/results.md's commands).
std::map<std::string, std::string> ParseArgs(int argc, char** argv) {
  std::map<std::string, std::string> args;
  const char* positional[] = {"scenes", "erosion", "seed"};
  size_t next_positional = 0;
  for (const bench::Argument& a : bench::Arguments(argc, argv)) {
    if (a.has_value) {
      args[a.key] = a.value;
    } else if (next_positional < 3) {
      args[positional[next_positional++]] = a.text;
    }
  }
  return args;
}

// What one run measures: the scenes, the board and the pipeline's options.
struct Setup {
  int count = 12;
  uint64_t seed = 1;
  std::string erosion = "affine", covariance = "edge_noise";
  std::string rows = "all";  ///< "all", "blur" (rows starting "blur 1.4") or part of a name
  AprilGridSpec board = scenes::PaperBoard();
  PipelineOptions options;
};

bool ReadSetup(int argc, char** argv, Setup* setup) {
  std::map<std::string, std::string> args = ParseArgs(argc, argv);
  const auto value = [&](const char* key, const char* fallback) {
    const auto it = args.find(key);
    const std::string found = it == args.end() ? fallback : it->second;
    if (it != args.end()) args.erase(it);
    return found;
  };
  // A number, or `fallback` (the library's default) when not given.
  const auto number = [&](const char* key, double fallback) {
    const std::string text = value(key, "");
    return text.empty() ? fallback : std::atof(text.c_str());
  };
  setup->count = std::atoi(value("scenes", "12").c_str());
  setup->erosion = value("erosion", "affine");
  setup->seed = std::strtoull(value("seed", "1").c_str(), nullptr, 10);
  setup->covariance = value("covariance", "edge_noise");
  setup->board.layout =
      value("board", "legacy") == "kalibr" ? AprilGridLayout::kKalibr : AprilGridLayout::kH4Legacy;
  PoseOptions& pose = setup->options.pose;
  pose.corner_floor_px = number("corner_floor_px", pose.corner_floor_px);
  EdgeFitOptions& edge_fit = setup->options.detector.edge_fit;
  edge_fit.inner_clearance_px = number("inner_clearance_px", edge_fit.inner_clearance_px);
  edge_fit.inner_clearance_blur = number("inner_clearance_blur", edge_fit.inner_clearance_blur);
  setup->rows = value("conditions", "all");
  edge_fit.model_inner_edge = value("inner_edge", "inner") != "clear";
  edge_fit.band_px = number("band_px", edge_fit.band_px);
  if (!args.empty() || setup->count < 1) {
    fmt::print(stderr, "unknown argument '{}' or scenes < 1 (see the comment at the top of {})\n",
               args.empty() ? "" : args.begin()->first.c_str(), __FILE__);
    return false;
  }
  const std::string& covariance = setup->covariance;
  pose.covariance = covariance == "group"        ? CovarianceModel::kEdgeGroup
                    : covariance == "edge_noise" ? CovarianceModel::kEdgeNoise
                                                 : CovarianceModel::kResidual;
  const std::string& erosion = setup->erosion;
  pose.erosion = erosion == "none"     ? ErosionModel::kNone
                 : erosion == "tag"    ? ErosionModel::kPerTag
                 : erosion == "global" ? ErosionModel::kGlobal
                                       : ErosionModel::kAffine;
  return true;
}

void PrintSetup(const Setup& setup) {
  const EdgeFitOptions& edge_fit = setup.options.detector.edge_fit;
  fmt::print(
      "board {}, erosion model {}, covariance {}, corner floor {:.4f} px, {} scenes per "
      "condition, seed {}\n"
      "dark-side clearance {:.2f} px + {:.2f} blur sigma, inner edge {}, band {:.2f} px\n",
      setup.board.layout == AprilGridLayout::kKalibr ? "Kalibr's design" : "h4cam's earlier design",
      setup.erosion, setup.covariance, setup.options.pose.corner_floor_px, setup.count,
      static_cast<unsigned long long>(setup.seed), edge_fit.inner_clearance_px,
      edge_fit.inner_clearance_blur, edge_fit.model_inner_edge ? "modelled" : "kept clear",
      edge_fit.band_px);
  fmt::print("{:<46} {:>6} {:>9} {:>10} {:>7} {:>7} {:>10}\n", "condition", "scenes", "e_t_mm",
             "e_r_deg", "sig/t", "sig/r", "erosion_px");
}

// One condition's row: each scene rendered clean, degraded, averaged and measured.
void MeasureCondition(const Condition& condition, const Setup& setup,
                      const MeasurePipeline& pipeline, const std::vector<RigidTransform>& poses,
                      cv::RNG& rng) {
  const CameraIntrinsics camera = scenes::PaperCamera();
  Sums sums;
  for (size_t i = 0; i < poses.size(); ++i) {
    RenderOptions render;
    render.blur_sigma_px = rng.uniform(condition.blur_px_min, condition.blur_px_max + 1e-12);
    const BoardRenderer renderer(setup.board, camera, render);
    bench::DegradeOptions degrade;
    degrade.gamma = rng.uniform(condition.gamma_min, condition.gamma_max + 1e-12);
    degrade.gradient = condition.gradient;
    degrade.gradient_angle = rng.uniform(0.0, 2 * std::numbers::pi);
    degrade.read_noise = condition.read_noise;
    degrade.shot_noise = condition.shot_noise;
    const cv::Mat mean =
        bench::DegradedMean(renderer.RenderClean(poses[i]), degrade, 10, setup.seed * 1000 + i);
    MeasureScene(pipeline, mean, poses[i], &sums);
  }
  const int n = std::max(sums.used, 1);
  fmt::print("{:<46} {:3}/{:<2} {:>9.5f} {:>10.6f} {:>7.2f} {:>7.2f} {:>10.4f}\n", condition.name,
             sums.used, setup.count, std::sqrt(sums.err_t2 / n) * 1e3,
             DegreesFromRadians(std::sqrt(sums.err_r2 / n)), std::sqrt(sums.sig_t2 / sums.err_t2),
             std::sqrt(sums.sig_r2 / sums.err_r2), sums.erosion_px / n);
}

// The table: a row per chosen condition, over the same poses.
int Run(const Setup& setup) {
  MeasurePipeline pipeline(setup.board, scenes::PaperCamera(), setup.options);
  if (!pipeline.ok()) {
    fmt::print(stderr, "setup failed: {}\n", pipeline.error());
    return 1;
  }
  PrintSetup(setup);
  const auto poses = scenes::RandomPoses(setup.count, setup.seed);
  cv::RNG rng(setup.seed + 7);
  const auto start = std::chrono::steady_clock::now();
  for (const Condition& condition : Conditions()) {
    const std::string& rows = setup.rows;
    const bool wanted =
        rows == "all" || (rows == "blur" ? condition.name.rfind("blur 1.4", 0) == 0
                                         : condition.name.find(rows) != std::string::npos);
    if (wanted) MeasureCondition(condition, setup, pipeline, poses, rng);
  }
  fmt::print("total {:.1f} s\n", SecondsSince(start));
  return 0;
}

}  // namespace
}  // namespace h4::cam

int main(int argc, char** argv) {
  return h4::cam::bench::RunOnArguments(argc, argv, h4::cam::ReadSetup, h4::cam::Run);
}
