// Accuracy benchmark of the measuring pipeline on rendered scenes like the paper's
// (1024 x 768, ~817 px focal length, mild distortion, 6 x 6 tags of 30 mm at 0.45-0.65 m
// tilted up to 25 deg, noise 2 grey levels per frame, 10 frames averaged). Prints one
// row per scene and the summary against the goals: position error RMS <= 0.05 mm,
// rotation error RMS <= 0.01 deg, reported sigma within a factor 2 of the actual error.
// Usage: h4_measure_accuracy [scenes=30] [refinement=edge|subpix|none] [seed=1]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/geometry/rotation.h"
#include "firmware/pose/measure_pipeline.h"
#include "firmware/render/paper_scenes.h"
#include "firmware/sources/sim_source.h"

int main(int argc, char** argv) {
  using namespace h4;
  using namespace h4::cam;
  const int count = argc > 1 ? std::atoi(argv[1]) : 30;
  const std::string refinement = argc > 2 ? argv[2] : "edge";
  const uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
  const AprilGridSpec board = scenes::PaperBoard();
  const CameraIntrinsics camera = scenes::PaperCamera();
  PipelineOptions options;
  options.detector.refinement = refinement == "subpix" ? CornerRefinement::kCornerSubPix
                                : refinement == "none" ? CornerRefinement::kNone
                                                       : CornerRefinement::kEdgeFit;
  SimSourceOptions sim;
  sim.seed = seed;
  SimSource source(board, camera, sim);
  MeasurePipeline pipeline(board, camera, options);
  if (!source.Open() || !pipeline.ok()) {
    std::fprintf(stderr, "setup failed: %s %s\n", source.error().c_str(), pipeline.error().c_str());
    return 1;
  }
  std::printf("refinement %s, %d scenes, seed %llu\n", refinement.c_str(), count,
              static_cast<unsigned long long>(seed));
  std::printf("%5s %7s %7s %7s %8s %9s %10s %9s %10s %s\n", "scene", "z_m", "tilt_deg", "corners",
              "rms_px", "e_t_mm", "e_r_deg", "sig_t_mm", "sig_r_deg", "status");
  double err_t2 = 0, err_r2 = 0, sig_t2 = 0, sig_r2 = 0;
  int used = 0;
  const auto poses = scenes::RandomPoses(count, seed);
  for (size_t i = 0; i < poses.size(); ++i) {
    const RigidTransform& X_CT = poses[i];
    source.SetPose(X_CT);
    std::optional<Measurement> m;
    while (!m) m = pipeline.AddFrame(*source.Next(std::chrono::milliseconds(0)));
    const double tilt = std::acos(std::clamp(X_CT.rotation()(2, 2), -1.0, 1.0)) * 180 / M_PI;
    if (!m->ok()) {
      std::printf("%5zu %7.3f %7.1f %7d %8s %9s %10s %9s %10s %s\n", i, X_CT.translation().z(),
                  tilt, m->corners_used, "-", "-", "-", "-", "-", ToString(m->status));
      continue;
    }
    const Eigen::Vector3d e_t = m->X_CT.translation() - X_CT.translation();
    const Eigen::Vector3d e_r = So3Log(X_CT.rotation().transpose() * m->X_CT.rotation());
    err_t2 += e_t.squaredNorm();
    err_r2 += e_r.squaredNorm();
    sig_t2 += 3 * m->sigma_t * m->sigma_t;  // sigma_t is per axis
    sig_r2 += 3 * m->sigma_r * m->sigma_r;
    ++used;
    std::printf("%5zu %7.3f %7.1f %7d %8.4f %9.5f %10.6f %9.5f %10.6f %s\n", i,
                X_CT.translation().z(), tilt, m->corners_used, m->rms_px, e_t.norm() * 1e3,
                e_r.norm() * 180 / M_PI, m->sigma_t * 1e3, m->sigma_r * 180 / M_PI,
                ToString(m->status));
  }
  if (used == 0) {
    std::printf("no scene measured\n");
    return 1;
  }
  const double rms_t = std::sqrt(err_t2 / used), rms_r = std::sqrt(err_r2 / used);
  const double ratio_t = std::sqrt(sig_t2 / err_t2), ratio_r = std::sqrt(sig_r2 / err_r2);
  const bool ok = rms_t <= 0.05e-3 && rms_r <= 0.01 * M_PI / 180 && ratio_t >= 0.5 &&
                  ratio_t <= 2 && ratio_r >= 0.5 && ratio_r <= 2;
  std::printf("\nmeasured %d/%d scenes\n", used, count);
  std::printf("position error RMS  %.5f mm   (goal <= 0.05 mm)\n", rms_t * 1e3);
  std::printf("rotation error RMS  %.6f deg (goal <= 0.01 deg)\n", rms_r * 180 / M_PI);
  std::printf("reported/actual sigma: position %.2f, rotation %.2f (goal within 0.5..2)\n", ratio_t,
              ratio_r);
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 2;
}
