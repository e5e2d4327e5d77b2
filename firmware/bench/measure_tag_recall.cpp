// Tag recall through a wide-angle lens (issue 28): Kalibr's 88 mm 6 x 6 aprilgrid rendered
// (the "processed" preset: sRGB response, defocus, light gradient, vignetting, shot noise)
// through a camera file at random poses, the board anywhere in the field of view, rolled
// up to 45 deg and tilted up to 30 deg, and detected. Counts the tags whose whole border
// images inside the frame, how many of them were found with every corner where the truth
// puts it, how many the quad search alone found, and tags reported in a wrong place
// (tag_recall.h). Prints the totals and the scenes that missed a tag.
//
// Usage: h4_measure_tag_recall [camera=boards/sim_fisheye_190deg_1024x1024.yaml]
//                              [scenes=100] [seed=1] [max_off_axis_deg=80]
//                              [distance=0.4,1.2] [preset=processed|clean]
// (paths relative to the source tree, or absolute)
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include <fmt/core.h>
#include <opencv2/core.hpp>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "firmware/bench/bench_arguments.h"
#include "firmware/bench/tag_recall.h"
#include "firmware/render/board_renderer.h"

namespace h4::cam {
namespace {

struct Args {
  std::string camera = "boards/sim_fisheye_190deg_1024x1024.yaml";
  int scenes = 100;
  uint64_t seed = 1;
  double max_off_axis_deg = 80;
  double min_distance = 0.4, max_distance = 1.2;
  bool clean = false;
};

bool ParseArgs(int argc, char** argv, Args* args) {
  for (const bench::Argument& a : bench::Arguments(argc, argv)) {
    const std::string &arg = a.text, &key = a.key, &value = a.value;
    if (key == "camera" && !value.empty()) {
      args->camera = value;
    } else if (key == "scenes") {
      args->scenes = std::atoi(value.c_str());
    } else if (key == "seed") {
      args->seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (key == "max_off_axis_deg") {
      args->max_off_axis_deg = std::atof(value.c_str());
    } else if (key == "distance" && std::sscanf(value.c_str(), "%lf,%lf", &args->min_distance,
                                                &args->max_distance) == 2) {
    } else if (key == "preset" && (value == "processed" || value == "clean")) {
      args->clean = value == "clean";
    } else {
      fmt::print(stderr, "unknown argument '{}' (see the comment at the top of {})\n", arg,
                 __FILE__);
      return false;
    }
  }
  if (args->scenes < 1 || !(args->min_distance > 0 && args->min_distance <= args->max_distance)) {
    fmt::print(stderr, "scenes must be >= 1 and distance MIN,MAX with 0 < MIN <= MAX\n");
    return false;
  }
  return true;
}

std::string InSource(const std::string& path) {
  return path.empty() || path[0] == '/' ? path : std::string(H4_SOURCE_DIR) + "/" + path;
}

// A random scene: the board's centre in a direction drawn uniformly over the cap within
// max_off_axis_deg of the axis, at a random distance, rolled and tilted.
bench::Scene RandomScene(const Args& args, cv::RNG& rng) {
  const double cos_max = std::cos(RadiansFromDegrees(args.max_off_axis_deg));
  const double off_axis = DegreesFromRadians(std::acos(rng.uniform(cos_max, 1.0)));
  return {"random",
          off_axis,
          rng.uniform(0.0, 360.0),
          rng.uniform(args.min_distance, args.max_distance),
          rng.uniform(-45.0, 45.0),
          rng.uniform(-30.0, 30.0)};
}

// The scenes that missed a tag as they come, then the totals.
int Run(const Args& args) {
  const AprilGridSpec grid =
      std::get<AprilGridSpec>(ReadBoardYaml(InSource("boards/kalibr_aprilgrid_6x6_88mm.yaml")));
  const CameraIntrinsics intrinsics = ReadCameraYaml(InSource(args.camera));
  const BoardModel board(grid);
  const CameraModel camera(intrinsics);
  const BoardRenderer renderer(grid, intrinsics,
                               args.clean ? RenderOptions::Clean() : RenderOptions::Processed());
  const BoardDetector detector(grid, intrinsics);
  if (!renderer.ok() || !detector.ok()) {
    fmt::print(stderr, "setup failed: {}{}\n", renderer.error(), detector.error());
    return 1;
  }
  fmt::print("{}, {} scenes, seed {}, off-axis up to {:.0f} deg, {:.2f}-{:.2f} m, {} preset\n",
             args.camera, args.scenes, static_cast<unsigned long long>(args.seed),
             args.max_off_axis_deg, args.min_distance, args.max_distance,
             args.clean ? "clean" : "processed");
  cv::RNG rng(args.seed);
  bench::TagCount total;
  int quad_search_found = 0, scenes_with_tags = 0, scenes_missing = 0;
  std::map<TagMiss, int> why_missed;
  for (int i = 0; i < args.scenes; ++i) {
    const bench::Scene scene = RandomScene(args, rng);
    const RigidTransform X_CT = bench::BoardFacingCamera(board, scene);
    const BoardDetection detection = detector.Detect(renderer.Render(X_CT, args.seed * 1000 + i));
    const bench::TagCount count = bench::CountTags(board, camera, X_CT, detection);
    if (count.expected == 0) continue;
    ++scenes_with_tags;
    total.expected += count.expected;
    total.found += count.found;
    total.misplaced += count.misplaced;
    quad_search_found += count.found - detection.tags_predicted;
    for (const MissedTag& miss : detection.missed) ++why_missed[miss.why];
    if (count.found < count.expected || count.misplaced > 0) {
      ++scenes_missing;
      fmt::print(
          "  scene {} ({:.1f} deg off-axis, azimuth {:.1f}, {:.3f} m, roll {:.1f}, tilt {:.1f}): "
          "{} of {} found, {} misplaced (detection: {} tags, {} rejected, {} ids seen twice)\n",
          i, scene.off_axis_deg, scene.azimuth_deg, scene.distance, scene.roll_deg, scene.tilt_deg,
          count.found, count.expected, count.misplaced, detection.tags, detection.tags_rejected,
          detection.ids_seen_twice);
    }
  }
  fmt::print(
      "tags wholly in the image: {} in {} scenes; found {} ({:.2f} %), quad search alone {} "
      "({:.2f} %); tags misplaced {}; scenes missing a tag {}\n",
      total.expected, scenes_with_tags, total.found,
      100.0 * total.found / std::max(total.expected, 1), quad_search_found,
      100.0 * quad_search_found / std::max(total.expected, 1), total.misplaced, scenes_missing);
  for (const auto& [why, n] : why_missed) fmt::print("  missed, {}: {}\n", ToString(why), n);
  return 0;
}

}  // namespace
}  // namespace h4::cam

int main(int argc, char** argv) {
  return h4::cam::bench::RunOnArguments(argc, argv, h4::cam::ParseArgs, h4::cam::Run);
}
