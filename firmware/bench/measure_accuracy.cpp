// Accuracy benchmark of the measuring pipeline on rendered scenes like the paper's
// (1024 x 768, ~817 px focal length, mild distortion, 6 x 6 tags of 30 mm at 0.45-0.65 m
// tilted up to 25 deg, 10 frames averaged), under image conditions a real camera adds
// (firmware/render/render_options.h): blur, a non-linear response, an illumination
// gradient, all of them together. Side by side on the same frames: the h4cam pipeline
// (MeasurePipeline) and a plain baseline (the averaged image, libapriltag's corners as they
// come, OpenCV's IPPE + Levenberg-Marquardt with the same intrinsics). Prints a markdown
// table: position and rotation error RMS, reported sigma / actual error, CPU time per pose.
//
// Usage: h4_measure_accuracy [condition=NAME|every] [depth=range|near|far|close|every]
//                            [scenes=20] [seed=1] [refinement=edge|xcorner|subpix|none] [rows]
//                            [corner_floor_px=0.0015] [covariance=edge_noise|residual|group]
//                            [corner_floor_erosion_gain=0.02] (PoseOptions' fields)
//                            [camera=FILE] (a camera YAML instead of the paper's: e.g.
//                            boards/sim_fisheye_190deg_1024x1024.yaml renders and measures
//                            through the equidistant fisheye)
//                            [board=legacy|kalibr] (the paper's 6 x 6 30 mm grid in h4cam's
//                            earlier design, or in Kalibr's: 2-cell borders, corner squares)
//                            [pixel_blur_check_deg=6] (EdgeFitOptions' field; 0: the optical
//                            blur profile alone)
//                            [roll=any|aligned] (aligned: the boards turned by a multiple of
//                            90 deg and hardly tilted, every tag's sides along the pixel axes,
//                            where an edge model that blurs differently from the image locks to
//                            the pixel grid: firmware/detection/edge_refinement.h)
// Conditions: clean, blur1.4, gamma0.7+blur0.7, srgb+blur1.0, gradient, all (the
// "processed" preset: sRGB, defocus, gradient, vignetting, shot noise). Depths: range
// 0.45-0.65 m, near 0.44-0.46 m, far 0.64-0.66 m, close 0.25-0.35 m. `rows` prints every
// scene.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>

#include "common/camera/camera_model.h"
#include "common/formats/camera_yaml.h"
#include "common/geometry/rotation.h"
#include "common/units.h"
#include "firmware/bench/bench_arguments.h"
#include "firmware/bench/bench_conditions.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {
namespace {

using bench::AllConditions;
using bench::Condition;

struct DepthRange {
  const char* name;
  double min_depth, max_depth;  // m
};

// "close": where a wide-angle lens (e.g. the 190-degree fisheye, f 309 px) images the 30 mm
// tags as large as the paper's camera does at 0.45-0.65 m (25-37 px).
const std::vector<DepthRange> kDepths = {
    {"range", 0.45, 0.65}, {"near", 0.44, 0.46}, {"far", 0.64, 0.66}, {"close", 0.25, 0.35}};

struct Args {
  std::string condition = "every", depth = "range", refinement = "edge";
  int scenes = 20;
  uint64_t seed = 1;
  bool rows = false;
  double corner_floor_px = PoseOptions{}.corner_floor_px;
  double corner_floor_erosion_gain = PoseOptions{}.corner_floor_erosion_gain;
  std::string covariance;
  std::string camera_path;  ///< "" = scenes::PaperCamera()
  AprilGridLayout layout = AprilGridLayout::kH4Legacy;
  bool aligned = false;
  double pixel_blur_check_deg = EdgeFitOptions{}.pixel_blur_check_deg;
};

bool ParseArgs(int argc, char** argv, Args* args) {
  for (const bench::Argument& a : bench::Arguments(argc, argv)) {
    const std::string &arg = a.text, &key = a.key, &value = a.value;
    if (arg == "rows") {
      args->rows = true;
    } else if (key == "condition") {
      args->condition = value;
    } else if (key == "depth") {
      args->depth = value;
    } else if (key == "refinement") {
      args->refinement = value;
    } else if (key == "scenes" || (!a.has_value && std::atoi(arg.c_str()) > 0)) {
      args->scenes = std::atoi((a.has_value ? value : arg).c_str());
    } else if (key == "seed") {
      args->seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (key == "covariance" &&
               (value == "residual" || value == "group" || value == "edge_noise")) {
      args->covariance = value;
    } else if (key == "corner_floor_erosion_gain") {
      args->corner_floor_erosion_gain = std::atof(value.c_str());
    } else if (key == "camera" && !value.empty()) {
      args->camera_path = value;
    } else if (key == "board" && (value == "legacy" || value == "kalibr")) {
      args->layout = value == "kalibr" ? AprilGridLayout::kKalibr : AprilGridLayout::kH4Legacy;
    } else if (key == "pixel_blur_check_deg") {
      args->pixel_blur_check_deg = std::atof(value.c_str());
    } else if (key == "roll" && (value == "any" || value == "aligned")) {
      args->aligned = value == "aligned";
    } else if (key == "corner_floor_px") {
      args->corner_floor_px = std::atof(value.c_str());
    } else {
      fmt::print(stderr, "unknown argument '{}'\n", arg);
      return false;
    }
  }
  if (args->scenes < 1 || args->scenes > 10000) {
    fmt::print(stderr, "scenes: expected 1..10000\n");
    return false;
  }
  return true;
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Sums over the scenes of one method.
struct Tally {
  int measured = 0;
  double err_t2 = 0, err_r2 = 0, sig_t2 = 0, sig_r2 = 0, cpu_s = 0;
  bool has_sigma = false;

  void Add(const RigidTransform& X_CT_true, const RigidTransform& X_CT, double sigma_t,
           double sigma_r) {
    err_t2 += (X_CT.translation() - X_CT_true.translation()).squaredNorm();
    err_r2 += So3Log(X_CT_true.rotation().transpose() * X_CT.rotation()).squaredNorm();
    sig_t2 += 3 * sigma_t * sigma_t;  // sigmas are per axis
    sig_r2 += 3 * sigma_r * sigma_r;
    ++measured;
  }
};

// OpenCV's IPPE, then Levenberg-Marquardt on all the points, in `K`'s pixels with
// `distortion` (radtan).
std::optional<RigidTransform> SolvePlainPnP(const std::vector<cv::Point3d>& object,
                                            const std::vector<cv::Point2d>& image, const cv::Mat& K,
                                            const cv::Mat& distortion) {
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, image, K, distortion, rvec, tvec, false, cv::SOLVEPNP_IPPE)) {
    return std::nullopt;
  }
  cv::solvePnPRefineLM(object, image, K, distortion, rvec, tvec);
  const Eigen::Vector3d r(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  const Eigen::Vector3d p_CT(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return RigidTransform(So3Exp(r), p_CT);
}

// The plain baseline on the averaged image: AprilTag corners, IPPE, then LM on all of them;
// radtan through OpenCV's own distortion, the equidistant fisheye on the corners' rays
// (CameraModel::RayFromPixel: cv::solvePnP has no fisheye model) with an identity K.
std::optional<RigidTransform> BaselinePose(const BoardDetector& detector,
                                           const CameraIntrinsics& camera, const cv::Mat& mean) {
  const BoardDetection detection = detector.Detect(mean);
  if (detection.corners.size() < 4) return std::nullopt;
  const CameraModel model(camera);
  const bool radtan = camera.distortion_model == DistortionModel::kRadTan;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector3d ray_C;
    if (!radtan && (!model.RayFromPixel(c.uv, &ray_C) || ray_C.z() <= 0)) continue;
    object.emplace_back(c.p_TQ.x(), c.p_TQ.y(), c.p_TQ.z());
    image.emplace_back(radtan ? cv::Point2d(c.uv.x(), c.uv.y())
                              : cv::Point2d(ray_C.x() / ray_C.z(), ray_C.y() / ray_C.z()));
  }
  if (object.size() < 4) return std::nullopt;
  if (!radtan) return SolvePlainPnP(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat());
  cv::Mat K(3, 3, CV_64F), distortion(static_cast<int>(camera.distortion.size()), 1, CV_64F);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) K.at<double>(r, c) = camera.K(r, c);
  }
  for (int k = 0; k < distortion.rows; ++k) distortion.at<double>(k) = camera.distortion(k);
  return SolvePlainPnP(object, image, K, distortion);
}

struct Result {
  Tally pipeline, baseline;
  int scenes = 0;
};

Result RunCondition(const Condition& condition, const DepthRange& depth, const Args& args,
                    const PipelineOptions& options) {
  AprilGridSpec board = scenes::PaperBoard();
  board.layout = args.layout;
  const CameraIntrinsics camera =
      args.camera_path.empty() ? scenes::PaperCamera() : ReadCameraYaml(args.camera_path);
  SimSourceOptions sim;
  sim.seed = args.seed;
  sim.render = condition.render;
  SimSource source(board, camera, sim);
  MeasurePipeline pipeline(board, camera, options);
  DetectorOptions plain;
  plain.refinement = CornerRefinement::kNone;
  const BoardDetector baseline(board, camera, plain);
  Result result;
  const auto poses =
      args.aligned ? scenes::AxisAlignedPoses(args.scenes, args.seed, depth.min_depth, depth.max_depth)
                   : scenes::RandomPoses(args.scenes, args.seed, depth.min_depth, depth.max_depth);
  for (size_t i = 0; i < poses.size(); ++i) {
    const RigidTransform& X_CT = poses[i];
    source.SetPose(X_CT);
    std::vector<Frame> frames;
    for (int k = 0; k < options.frames; ++k) {
      frames.push_back(*source.Next(std::chrono::milliseconds(0)));
    }
    double start = CpuSeconds();
    const Measurement m = pipeline.MeasureFrames(frames);
    result.pipeline.cpu_s += CpuSeconds() - start;
    if (m.ok()) result.pipeline.Add(X_CT, m.X_CT, m.sigma_t, m.sigma_r);

    start = CpuSeconds();
    FrameAverager averager(options.frames);
    for (const Frame& f : frames) averager.Add(f);
    const std::optional<RigidTransform> plain_pose =
        BaselinePose(baseline, camera, averager.Mean());
    result.baseline.cpu_s += CpuSeconds() - start;
    if (plain_pose) result.baseline.Add(X_CT, *plain_pose, 0, 0);
    ++result.scenes;
    if (args.rows) {
      auto error_mm = [&](bool ok, const RigidTransform& X) {
        return ok ? (X.translation() - X_CT.translation()).norm() * 1e3 : NAN;
      };
      fmt::print(
          "  {} {} scene {} z {:.3f} m: h4cam {} {:.4f} mm (sigma {:.4f} mm, rms {:.4f} px, "
          "erosion {:.3f} px), baseline {:.4f} mm\n",
          condition.name, depth.name, i, X_CT.translation().z(), ToString(m.status),
          error_mm(m.ok(), m.X_CT), m.sigma_t * 1e3, m.rms_px, m.erosion_px,
          error_mm(plain_pose.has_value(), plain_pose.value_or(X_CT)));
    }
  }
  result.pipeline.has_sigma = true;
  return result;
}

void PrintRow(const char* condition, const char* depth, const char* method, const Tally& t,
              int scenes) {
  if (t.measured == 0) {
    fmt::print("| {} | {} | {} | 0/{} | - | - | - | - |\n", condition, depth, method, scenes);
    return;
  }
  const double rms_t_mm = std::sqrt(t.err_t2 / t.measured) * 1e3;
  const double rms_r_deg = DegreesFromRadians(std::sqrt(t.err_r2 / t.measured));
  std::string ratio = "-";
  if (t.has_sigma) {
    ratio = fmt::format("{:.2f} / {:.2f}", std::sqrt(t.sig_t2 / t.err_t2),
                        std::sqrt(t.sig_r2 / t.err_r2));
  }
  fmt::print("| {} | {} | {} | {}/{} | {:.4f} | {:.5f} | {} | {:.1f} |\n", condition, depth, method,
             t.measured, scenes, rms_t_mm, rms_r_deg, ratio, t.cpu_s / scenes * 1e3);
}

// The table: each chosen condition at each chosen depth, h4cam beside the baseline.
int Run(const Args& args) {
  PipelineOptions options;
  options.detector.refinement = args.refinement == "subpix"    ? CornerRefinement::kCornerSubPix
                                : args.refinement == "none"    ? CornerRefinement::kNone
                                : args.refinement == "xcorner" ? CornerRefinement::kXCorner
                                                               : CornerRefinement::kEdgeFit;
  options.detector.edge_fit.pixel_blur_check_deg = args.pixel_blur_check_deg;
  options.pose.corner_floor_px = args.corner_floor_px;
  options.pose.corner_floor_erosion_gain = args.corner_floor_erosion_gain;
  if (args.covariance == "residual") options.pose.covariance = CovarianceModel::kResidual;
  if (args.covariance == "group") options.pose.covariance = CovarianceModel::kEdgeGroup;
  if (args.covariance == "edge_noise") options.pose.covariance = CovarianceModel::kEdgeNoise;
  std::vector<Condition> conditions;
  for (const Condition& c : AllConditions()) {
    if (args.condition == "every" || args.condition == c.name) conditions.push_back(c);
  }
  std::vector<DepthRange> depths;
  for (const DepthRange& d : kDepths) {
    if (args.depth == "every" || args.depth == d.name) depths.push_back(d);
  }
  if (conditions.empty() || depths.empty()) {
    fmt::print(stderr, "unknown condition '{}' or depth '{}'\n", args.condition, args.depth);
    return 1;
  }
  fmt::print(
      "{} scenes per row, seed {}, {} frames averaged, h4cam refinement {}, camera {}, board "
      "{}; baseline: AprilTag corners + IPPE + LM\n\n",
      args.scenes, static_cast<unsigned long long>(args.seed), options.frames, args.refinement,
      args.camera_path.empty() ? "the paper's" : args.camera_path.c_str(),
      args.layout == h4::AprilGridLayout::kKalibr ? "Kalibr's design" : "h4cam's earlier design");
  fmt::print(
      "| condition | depth | method | measured | position RMS mm | rotation RMS deg | "
      "sigma/actual pos / rot | CPU ms/pose |\n");
  fmt::print("|---|---|---|---|---|---|---|---|\n");
  for (const Condition& condition : conditions) {
    for (const DepthRange& depth : depths) {
      const Result r = RunCondition(condition, depth, args, options);
      PrintRow(condition.name, depth.name, "h4cam", r.pipeline, r.scenes);
      PrintRow(condition.name, depth.name, "baseline", r.baseline, r.scenes);
    }
  }
  return 0;
}

}  // namespace
}  // namespace h4::cam

int main(int argc, char** argv) {
  return h4::cam::bench::RunOnArguments(argc, argv, h4::cam::ParseArgs, h4::cam::Run);
}
