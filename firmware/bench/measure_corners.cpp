// Corner-level benchmark of the detector on rendered scenes like the paper's (the scenes of
// h4_measure_accuracy: 1024 x 768, f 817 px, 6 x 6 tags of 30 mm at 0.45-0.65 m, 10
// frames averaged), for either board design: where the pose error of a board comes from.
// Per condition, against the renderer's true projections: corners found, how many were
// edge-fitted, their RMS error, the part of it a uniform erosion explains (what the pose
// estimator fits away: firmware/pose/pose_estimator.h) and what is left, and the tags'
// rotation error (the corners of a tag turning together about its centre, which moves the
// board's rotation).
//
// Usage: h4_measure_corners [board=legacy|kalibr] [condition=NAME|every] [scenes=12]
//                           [seed=1] [refinement=edge|xcorner]
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
};

// One scene's corners against the true projections: the image's uniform erosion (least
// squares over its edge-fitted corners) taken out, and each tag's rotation about its centre.
void AddScene(const BoardDetection& detection, const CameraModel& camera,
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
  CornerTally tally;
  for (const RigidTransform& X_CT : scenes::RandomPoses(args.scenes, args.seed)) {
    source.SetPose(X_CT);
    FrameAverager averager(10);
    for (int k = 0; k < 10; ++k) averager.Add(*source.Next(std::chrono::milliseconds(0)));
    AddScene(detector.Detect(averager.Mean()), model, X_CT, &tally);
    tally.expected += BoardModel(board).corner_count();
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
      "RMS urad |\n|---|---|---|---|---|---|\n");
  for (const bench::Condition& condition : bench::AllConditions()) {
    if (args.condition != "every" && args.condition != condition.name) continue;
    const CornerTally t = RunCondition(condition, args);
    const double n = std::max(t.found, 1);
    fmt::print("| {} | {}/{} | {} | {:.4f} | {:.4f} | {:.1f} |\n", condition.name, t.found,
               t.expected, t.edge_fitted, std::sqrt(t.error2 / n), std::sqrt(t.after_erosion2 / n),
               1e6 * std::sqrt(t.tag_rotation2 / std::max(t.tags, 1)));
  }
  return 0;
}

}  // namespace
}  // namespace h4::cam

int main(int argc, char** argv) {
  return h4::cam::bench::RunOnArguments(argc, argv, h4::cam::ParseArgs, h4::cam::Run);
}
