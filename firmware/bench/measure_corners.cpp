// Corner-level benchmark of the detector on rendered scenes like the paper's (the scenes of
// h4_measure_accuracy: 1024 x 768, f 817 px, 6 x 6 tags of 30 mm at 0.45-0.65 m, 10
// frames averaged), for either board design: where the pose error of a board comes from.
// Per condition, against the renderer's true projections: corners found, how many were
// edge-fitted, their RMS error, the part of it a uniform erosion explains (what the pose
// estimator fits away: firmware/pose/pose_estimator.h) and what is left, and the tags'
// rotation error (the corners of a tag turning together about its centre, which moves the
// board's rotation). Then the corners h4cam exports (MeasurePipeline: `measure --corners-out`
// and the campaign's corners, less the erosion the pose fit explains): their mean shift toward
// their tag's centre (what a pixel-space fit downstream would read as a smaller board) against
// the detected corners', the fitted erosion against the least-squares erosion of the true
// errors, and the exported corners' RMS error on tags whose sides run within 3 deg of the
// pixel axes and on the others (pixel locking, firmware/detection/edge_refinement.h), and
// whether their stated sigma_px is honest: its RMS against the per-axis RMS error.
//
// Usage: h4_measure_corners [board=legacy|kalibr] [condition=NAME|every] [scenes=12]
//                           [seed=1] [refinement=edge|xcorner] [roll=any|aligned]
// roll=aligned: the boards turned by a multiple of 90 deg (+-0.5) and tilted at most 2 deg,
// so that every tag's sides run along the pixel axes.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "common/camera/camera_model.h"
#include "firmware/averaging/frame_averager.h"
#include "firmware/bench/bench_arguments.h"
#include "firmware/bench/bench_conditions.h"
#include "firmware/detection/board_detector.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {
namespace {

struct Args {
  AprilGridLayout layout = AprilGridLayout::kH4Legacy;
  std::string condition = "every";
  int scenes = 12;
  uint64_t seed = 1;
  CornerRefinement refinement = CornerRefinement::kEdgeFit;
  bool aligned = false;
};

bool ParseArgs(int argc, char** argv, Args* args) {
  for (const bench::Argument& a : bench::Arguments(argc, argv)) {
    const std::string &arg = a.text, &key = a.key, &value = a.value;
    if (key == "board" && (value == "legacy" || value == "kalibr")) {
      args->layout = value == "kalibr" ? AprilGridLayout::kKalibr : AprilGridLayout::kH4Legacy;
    } else if (key == "condition" && !value.empty()) {
      args->condition = value;
    } else if (key == "scenes" && std::atoi(value.c_str()) > 0) {
      args->scenes = std::atoi(value.c_str());
    } else if (key == "seed") {
      args->seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (key == "roll" && (value == "any" || value == "aligned")) {
      args->aligned = value == "aligned";
    } else if (key == "refinement" && (value == "edge" || value == "xcorner")) {
      args->refinement = value == "edge" ? CornerRefinement::kEdgeFit : CornerRefinement::kXCorner;
    } else {
      fmt::print(stderr, "unknown argument '{}' (see the comment at the top of {})\n", arg,
                 __FILE__);
      return false;
    }
  }
  return true;
}

// Sums over one condition's scenes.
struct CornerTally {
  int expected = 0, found = 0, edge_fitted = 0, tags = 0;
  double error2 = 0, after_erosion2 = 0, tag_rotation2 = 0;
  // The exported corners (MeasurePipeline) against the truth.
  int exported = 0, aligned = 0, tilted = 0, scenes_measured = 0;
  double inward_detected = 0, inward_exported = 0;  // sums of the shift toward the tag centre
  double aligned2 = 0, tilted2 = 0;                 // squared errors by tag orientation
  double erosion_fitted = 0, erosion_true = 0;      // sums over the measured scenes, px
  double stated2 = 0;                               // sum of the exported sigma_px^2 (per axis)
};

// The true projection of a board corner.
Eigen::Vector2d TrueUv(const CameraModel& camera, const RigidTransform& X_CT,
                       const Eigen::Vector3d& p_TQ) {
  Eigen::Vector2d uv;
  camera.Project(X_CT * p_TQ, &uv);
  return uv;
}

// Whether the sides of the tag whose true corners are `uv` run within 3 deg of the pixel axes.
bool AlongPixelAxes(const std::vector<Eigen::Vector2d>& uv) {
  for (size_t k = 0; k < uv.size(); ++k) {
    const Eigen::Vector2d side = uv[(k + 1) % uv.size()] - uv[k];
    const double angle = std::fmod(std::abs(std::atan2(side.y(), side.x())), M_PI / 2);
    if (std::min(angle, M_PI / 2 - angle) > 3.0 * M_PI / 180) return false;
  }
  return true;
}

// The exported corners of one scene against the truth, tag by tag (tags with four corners).
void AddExported(const Measurement& m, const BoardDetection& detection, const BoardModel& board,
                 const CameraModel& camera, const RigidTransform& X_CT, double erosion_true,
                 CornerTally* tally) {
  if (!m.ok()) return;
  ++tally->scenes_measured;
  tally->erosion_fitted += m.erosion_px;
  tally->erosion_true += erosion_true;
  std::map<int, std::vector<size_t>> by_tag;
  for (size_t i = 0; i < m.corners.size(); ++i) by_tag[m.corners[i].corner / 4].push_back(i);
  std::map<int, Eigen::Vector2d> detected;
  for (const CornerObservation& c : detection.corners) detected[c.id] = c.uv;
  for (const auto& [tag, members] : by_tag) {
    if (members.size() != 4) continue;
    std::vector<Eigen::Vector2d> truth;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (size_t i : members) {
      truth.push_back(TrueUv(camera, X_CT, *board.Corner(m.corners[i].corner)));
      centre += 0.25 * truth.back();
    }
    const bool along_axes = AlongPixelAxes(truth);
    for (size_t k = 0; k < members.size(); ++k) {
      const MeasuredCorner& c = m.corners[members[k]];
      const Eigen::Vector2d inward = (centre - truth[k]).normalized();
      const Eigen::Vector2d error = c.uv - truth[k];
      tally->inward_exported += error.dot(inward);
      tally->inward_detected += (detected[c.corner] - truth[k]).dot(inward);
      (along_axes ? tally->aligned2 : tally->tilted2) += error.squaredNorm();
      tally->stated2 += c.sigma_px * c.sigma_px;
      ++(along_axes ? tally->aligned : tally->tilted);
      ++tally->exported;
    }
  }
}

// One scene's corners against the true projections: the image's uniform erosion (least
// squares over its edge-fitted corners) taken out, and each tag's rotation about its centre.
double AddScene(const BoardDetection& detection, const CameraModel& camera,
                const RigidTransform& X_CT, CornerTally* tally) {
  std::vector<Eigen::Vector2d> errors;
  double erosion_num = 0, erosion_den = 0;
  for (const CornerObservation& c : detection.corners) {
    Eigen::Vector2d uv_true;
    camera.Project(X_CT * c.p_TQ, &uv_true);
    errors.push_back(c.uv - uv_true);
    erosion_num += c.erosion_px.dot(errors.back());
    erosion_den += c.erosion_px.squaredNorm();
    if (c.edge_group >= 0) ++tally->edge_fitted;
  }
  const double erosion = erosion_den > 0 ? erosion_num / erosion_den : 0;
  std::map<int, std::vector<size_t>> by_tag;
  for (size_t i = 0; i < detection.corners.size(); ++i) {
    const CornerObservation& c = detection.corners[i];
    tally->error2 += errors[i].squaredNorm();
    tally->after_erosion2 += (errors[i] - erosion * c.erosion_px).squaredNorm();
    by_tag[c.id / 4].push_back(i);
  }
  for (const auto& [tag, members] : by_tag) {
    if (members.size() != 4) continue;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (size_t i : members) centre += 0.25 * detection.corners[i].uv;
    double moment = 0, inertia = 0;  // rotation = sum r x e / sum |r|^2
    for (size_t i : members) {
      const Eigen::Vector2d r = detection.corners[i].uv - centre;
      const Eigen::Vector2d e = errors[i] - erosion * detection.corners[i].erosion_px;
      moment += r.x() * e.y() - r.y() * e.x();
      inertia += r.squaredNorm();
    }
    tally->tag_rotation2 += std::pow(moment / inertia, 2);
    ++tally->tags;
  }
  tally->found += static_cast<int>(detection.corners.size());
  return erosion;
}

// The scenes: the paper's random poses, or (roll=aligned) boards turned by a multiple of 90 deg
// and hardly tilted, whose tags' sides run along the pixel axes.
std::vector<RigidTransform> ScenePoses(const Args& args) {
  return args.aligned ? scenes::AxisAlignedPoses(args.scenes, args.seed)
                      : scenes::RandomPoses(args.scenes, args.seed);
}

CornerTally RunCondition(const bench::Condition& condition, const Args& args) {
  AprilGridSpec board = scenes::PaperBoard();
  board.layout = args.layout;
  const CameraIntrinsics camera = scenes::PaperCamera();
  SimSourceOptions sim;
  sim.seed = args.seed;
  sim.render = condition.render;
  SimSource source(board, camera, sim);
  DetectorOptions options;
  options.refinement = args.refinement;
  const BoardDetector detector(board, camera, options);
  const CameraModel model(camera);
  PipelineOptions pipeline_options;
  pipeline_options.detector = options;
  const MeasurePipeline pipeline(board, camera, pipeline_options);
  const BoardModel board_model(board);
  CornerTally tally;
  for (const RigidTransform& X_CT : ScenePoses(args)) {
    source.SetPose(X_CT);
    FrameAverager averager(10);
    for (int k = 0; k < 10; ++k) averager.Add(*source.Next(std::chrono::milliseconds(0)));
    const cv::Mat mean = averager.Mean();
    const BoardDetection detection = detector.Detect(mean);
    const double erosion = AddScene(detection, model, X_CT, &tally);
    AddExported(pipeline.MeasureImage(mean, 10), detection, board_model, model, X_CT, erosion,
                &tally);
    tally.expected += board_model.corner_count();
  }
  return tally;
}

// The table: a row per chosen condition.
int Run(const Args& args) {
  fmt::print(
      "{} scenes per row, seed {}, board {}, refinement {}\n\n", args.scenes,
      static_cast<unsigned long long>(args.seed),
      args.layout == h4::AprilGridLayout::kKalibr ? "Kalibr's design" : "h4cam's earlier design",
      args.refinement == CornerRefinement::kEdgeFit ? "edge" : "xcorner");
  fmt::print(
      "| condition | corners found | edge-fitted | RMS px | RMS less erosion px | tag rotation "
      "RMS urad | shift to tag centre, detected px | exported px | erosion fitted / true px | "
      "exported RMS px, sides along pixel axes (n) | tilted (n) | stated sigma_px / per-axis "
      "RMS |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const bench::Condition& condition : bench::AllConditions()) {
    if (args.condition != "every" && args.condition != condition.name) continue;
    const CornerTally t = RunCondition(condition, args);
    const double n = std::max(t.found, 1);
    const double exported = std::max(t.exported, 1), scenes = std::max(t.scenes_measured, 1);
    fmt::print(
        "| {} | {}/{} | {} | {:.4f} | {:.4f} | {:.1f} | {:+.4f} | {:+.4f} | {:.3f} / {:.3f} | "
        "{:.4f} ({}) | {:.4f} ({}) | {:.4f} / {:.4f} |\n",
        condition.name, t.found, t.expected, t.edge_fitted, std::sqrt(t.error2 / n),
        std::sqrt(t.after_erosion2 / n), 1e6 * std::sqrt(t.tag_rotation2 / std::max(t.tags, 1)),
        t.inward_detected / exported, t.inward_exported / exported, t.erosion_fitted / scenes,
        t.erosion_true / scenes, std::sqrt(t.aligned2 / std::max(t.aligned, 1)), t.aligned,
        std::sqrt(t.tilted2 / std::max(t.tilted, 1)), t.tilted, std::sqrt(t.stated2 / exported),
        std::sqrt((t.aligned2 + t.tilted2) / (2 * exported)));
  }
  return 0;
}

}  // namespace
}  // namespace h4::cam

int main(int argc, char** argv) {
  return h4::cam::bench::RunOnArguments(argc, argv, h4::cam::ParseArgs, h4::cam::Run);
}
