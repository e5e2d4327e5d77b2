// Speed of the measuring pipeline at 1024 x 768 on one core (Google Benchmark): the
// frame-add path (must keep up with 30 fps: well under 33 ms), and the per-pose work
// (average 10 frames -> detect -> motion check -> pose; target under 30 ms), with its parts.
// The per-pose and pose benchmarks run with each erosion model (pose_estimator.h; argument
// 0 none, 1 global, 2 affine) so that the cost of the erosion parameters shows in one run;
// the per-pose work also on the same board in Kalibr's design (MeasureGroupOf10Kalibr:
// 2-cell borders, corner squares; argument 0 the edge fit from the X-corners, 1 the
// X-corners alone).
#include <benchmark/benchmark.h>

#include "firmware/detection/board_detector.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"

namespace h4::cam {
namespace {

AprilGridSpec BoardIn(AprilGridLayout layout) {
  AprilGridSpec board = scenes::PaperBoard();
  board.layout = layout;
  return board;
}

// The board tilted and rolled (its tags' sides at every angle to the pixel axes), or facing
// the camera square (kAxisAligned: every side along a pixel axis, each fitted with both blur
// stages, edge_refinement.h).
enum class Roll { kTilted, kAxisAligned };

RigidTransform PoseFor(Roll roll) {
  return roll == Roll::kTilted ? scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.8, 0.4)
                               : scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.01, 0.8, 0.002);
}

struct Scene {
  explicit Scene(AprilGridLayout layout = AprilGridLayout::kH4Legacy, Roll roll = Roll::kTilted)
      : source(BoardIn(layout), scenes::PaperCamera(), SimSourceOptions{}) {
    source.SetPose(PoseFor(roll));
    for (int k = 0; k < 10; ++k) frames.push_back(*source.Next(std::chrono::milliseconds(0)));
    FrameAverager averager(10);
    for (const Frame& f : frames) averager.Add(f);
    mean = averager.Mean();
  }
  SimSource source;
  std::vector<Frame> frames;
  cv::Mat mean;
};

const Scene& TheScene() {
  static const Scene scene;
  return scene;
}

void BM_AddFrame(benchmark::State& state) {
  const Scene& scene = TheScene();
  FrameAverager averager(1 << 30);
  for (auto _ : state) {
    averager.Add(scene.frames[0]);
    if (averager.count() > 1000) averager.Reset();
  }
}
BENCHMARK(BM_AddFrame)->Unit(benchmark::kMillisecond);

ErosionModel ErosionArg(const benchmark::State& state) {
  return static_cast<ErosionModel>(state.range(0));
}

void BM_MeasureGroupOf10(benchmark::State& state) {
  const Scene& scene = TheScene();
  PipelineOptions options;
  options.pose.erosion = ErosionArg(state);
  MeasurePipeline pipeline(scenes::PaperBoard(), scenes::PaperCamera(), options);
  for (auto _ : state) {
    std::optional<Measurement> m;
    for (const Frame& f : scene.frames) m = pipeline.AddFrame(f);
    if (!m || !m->ok()) state.SkipWithError("measurement failed");
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_MeasureGroupOf10)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// Argument 0: the default refinement (edge fit from the X-corners); 1: the X-corners alone.
void BM_MeasureGroupOf10Kalibr(benchmark::State& state) {
  static const Scene scene(AprilGridLayout::kKalibr);
  PipelineOptions options;
  if (state.range(0) == 1) options.detector.refinement = CornerRefinement::kXCorner;
  MeasurePipeline pipeline(BoardIn(AprilGridLayout::kKalibr), scenes::PaperCamera(), options);
  for (auto _ : state) {
    std::optional<Measurement> m;
    for (const Frame& f : scene.frames) m = pipeline.AddFrame(f);
    if (!m || !m->ok()) state.SkipWithError("measurement failed");
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_MeasureGroupOf10Kalibr)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_DetectEdgeFit(benchmark::State& state) {
  const Scene& scene = TheScene();
  const BoardDetector detector(scenes::PaperBoard(), scenes::PaperCamera());
  for (auto _ : state) benchmark::DoNotOptimize(detector.Detect(scene.mean));
}
BENCHMARK(BM_DetectEdgeFit)->Unit(benchmark::kMillisecond);

// Sides along the pixel axes: argument 0 with the pixel-blur refit (the default), 1 without
// (EdgeFitOptions::pixel_blur_check_deg = 0): what the refit costs where it runs.
void BM_DetectEdgeFitAxisAligned(benchmark::State& state) {
  static const Scene scene(AprilGridLayout::kH4Legacy, Roll::kAxisAligned);
  DetectorOptions options;
  if (state.range(0) == 1) options.edge_fit.pixel_blur_check_deg = 0.0;
  const BoardDetector detector(scenes::PaperBoard(), scenes::PaperCamera(), options);
  for (auto _ : state) benchmark::DoNotOptimize(detector.Detect(scene.mean));
}
BENCHMARK(BM_DetectEdgeFitAxisAligned)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_DetectAprilTagOnly(benchmark::State& state) {
  const Scene& scene = TheScene();
  DetectorOptions options;
  options.refinement = CornerRefinement::kNone;
  const BoardDetector detector(scenes::PaperBoard(), scenes::PaperCamera(), options);
  for (auto _ : state) benchmark::DoNotOptimize(detector.Detect(scene.mean));
}
BENCHMARK(BM_DetectAprilTagOnly)->Unit(benchmark::kMillisecond);

void BM_Pose(benchmark::State& state) {
  const Scene& scene = TheScene();
  const BoardDetector detector(scenes::PaperBoard(), scenes::PaperCamera());
  const BoardDetection detection = detector.Detect(scene.mean);
  const CameraModel camera(scenes::PaperCamera());
  PoseOptions options;
  options.erosion = ErosionArg(state);
  for (auto _ : state) benchmark::DoNotOptimize(EstimatePose(detection.corners, camera, options));
}
BENCHMARK(BM_Pose)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_RenderClean(benchmark::State& state) {
  const BoardRenderer renderer(scenes::PaperBoard(), scenes::PaperCamera(), RenderOptions{});
  const RigidTransform X_CT = scenes::BoardPose(scenes::PaperBoard(), 0.55, 0.3, 0.8, 0.4);
  for (auto _ : state) benchmark::DoNotOptimize(renderer.RenderClean(X_CT));
}
BENCHMARK(BM_RenderClean)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace h4::cam

BENCHMARK_MAIN();
