// The theta-singularity study (host/planning, CandidateOptions::max_theta_gain): over the
// default candidate grid without the singularity rule, the a priori nacelle-angle gain
// |d theta / dq| of each pose against the same pose on simulated Model 31 robots: their
// gain, and whether forward kinematics of the true robot, started at the true pose, still
// has a solution at its joints read with encoder noise (`h4cal simulate`'s 2e-5 rad).
// Where it has none, the measurement-space identification cannot be evaluated.
//
//   h4_singularity_study [--robots R] [--draws D] [--source-dir DIR]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "common/formats/board_yaml.h"
#include "common/formats/camera_yaml.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"
#include "host/kinematics/paper_robot.h"
#include "host/planning/candidate_poses.h"
#include "host/simulation/true_robot.h"

namespace h4::host {
namespace {

struct GainBin {
  double low = 0.0, high = 0.0;
  int poses = 0;
  std::vector<double> true_gains;
  int fk_trials = 0, fk_failures = 0;
};

std::vector<GainBin> MakeBins() {
  const double edges[] = {0, 4, 8, 12, 16, 25, 50, 100, INFINITY};
  std::vector<GainBin> bins;
  for (size_t k = 0; k + 1 < std::size(edges); ++k) {
    GainBin bin;
    bin.low = edges[k];
    bin.high = edges[k + 1];
    bins.push_back(bin);
  }
  return bins;
}

// One candidate on one true robot: its gain there and `draws` noisy-joint FK attempts.
void ExamineOnTruth(const SimulatedRobot& truth, const KinematicModel& true_model,
                    const CandidatePose& pose, int draws, std::mt19937_64* rng, GainBin* bin) {
  const EePose x = EePoseInB31(pose.x_B, truth.X_ModelB());
  const IkResult ik = true_model.InverseKinematics(x);
  if (!ik.ok()) return;
  bin->true_gains.push_back(ThetaJointGain(true_model, ik.q, x));
  std::normal_distribution<double> encoder_noise(0.0, 2e-5);
  for (int d = 0; d < draws; ++d) {
    JointVector q = ik.q;
    for (int i = 0; i < 4; ++i) q[i] += encoder_noise(*rng);
    ++bin->fk_trials;
    if (!ForwardKinematics(true_model, q, x).ok()) ++bin->fk_failures;
  }
}

double Quantile(std::vector<double> values, double p) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(p * static_cast<double>(values.size() - 1))];
}

int Run(int robots, int draws, const std::string& source_dir) {
  const RobotDescription apriori = PaperAprioriRobot();
  CandidateOptions options;
  options.max_theta_gain = INFINITY;  // every pose the image and the reach allow
  const CandidateSet set = MakeCandidateSet(
      apriori, CameraModel(ReadCameraYaml(source_dir + "/boards/sim_camera_1024x768.yaml")),
      BoardModel(ReadBoardYaml(source_dir + "/boards/aprilgrid_6x6_30mm.yaml")), options);
  fmt::print("{} (no singularity rule)\n", set.Summary());
  const Model12 model(apriori.model12, apriori.assembly);
  std::vector<GainBin> bins = MakeBins();
  std::mt19937_64 rng(1);
  for (int robot = 1; robot <= robots; ++robot) {
    const SimulatedRobot truth = MakeTrueRobot(apriori, TrueGeometry::kPerturbedModel31,
                                               {.seed = static_cast<uint64_t>(robot)});
    const std::unique_ptr<KinematicModel> true_model = truth.MakeModel();
    for (const CandidatePose& pose : set.poses) {
      const double gain = ThetaJointGain(model, pose.q, pose.x_B);
      for (GainBin& bin : bins) {
        if (gain < bin.low || gain >= bin.high) continue;
        if (robot == 1) ++bin.poses;
        ExamineOnTruth(truth, *true_model, pose, draws, &rng, &bin);
      }
    }
  }
  fmt::print("\n| a priori gain | poses | true gain, median / max | FK fails at noisy joints |\n");
  fmt::print("|---|---|---|---|\n");
  for (const GainBin& bin : bins) {
    fmt::print("| {:g}-{:g} | {} | {:.3g} / {:.3g} | {} of {} |\n", bin.low, bin.high, bin.poses,
               Quantile(bin.true_gains, 0.5), Quantile(bin.true_gains, 1.0), bin.fk_failures,
               bin.fk_trials);
  }
  return 0;
}

}  // namespace
}  // namespace h4::host

int main(int argc, char** argv) {
  int robots = 5, draws = 4;
  std::string source_dir = H4_SOURCE_DIR;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--robots") {
      robots = std::atoi(argv[i + 1]);
    } else if (flag == "--draws") {
      draws = std::atoi(argv[i + 1]);
    } else if (flag == "--source-dir") {
      source_dir = argv[i + 1];
    } else {
      fmt::print(stderr, "h4_singularity_study: unknown option {}\n", flag);
      return 1;
    }
  }
  return h4::host::Run(robots, draws, source_dir);
}
