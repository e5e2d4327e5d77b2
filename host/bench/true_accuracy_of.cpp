// Scores results against a simulation's truth (host/validation/true_accuracy.h), for the
// studies whose campaigns run through both programs (host/bench/image_study.sh): where the
// true robot goes when driven through each identified model over the paper's 81 grid
// poses, after the rigid registration of the base frame, beside what the result predicts.
//   h4_true_accuracy --truth truth.yaml --result R.json [--result R2.json ...]
// One line per result: poses reached, true registered RMS and max (mm), Z scale (ppm), the
// result's predicted robot and position accuracies (mm), their ratio to the truth, its
// verdict, and the refined fx, cx (px) when the result carries a camera.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "host/bench/study_main.h"
#include "host/formats/identification_result.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/truth_file.h"
#include "host/validation/true_accuracy.h"

namespace h4::host {
namespace {

struct Options {
  std::string truth;
  std::vector<std::string> results;
};

Options Parse(int argc, char** argv) {
  Options o;
  ForEachFlagAndValue(argc, argv, [&](const std::string& flag, const std::string& value) {
    if (flag == "--truth") {
      o.truth = value;
    } else if (flag == "--result") {
      o.results.push_back(value);
    } else {
      throw std::invalid_argument("unknown option '" + flag + "' (--truth FILE --result FILE...)");
    }
  });
  if (o.truth.empty() || o.results.empty()) {
    throw std::invalid_argument("usage: h4_true_accuracy --truth truth.yaml --result R.json...");
  }
  return o;
}

void Run(const Options& o) {
  const SimulationTruth truth = ReadTruthYaml(o.truth);
  std::vector<EePose> grid;
  for (const PlannedPose& p : GridPosePlan()) grid.push_back(p.x);
  for (const std::string& path : o.results) {
    const IdentificationResult result = ReadIdentificationResult(path);
    const TrueAccuracy t = TrueAccuracyOfResult(result, truth.robot, grid);
    const double robot = result.predicted_robot_accuracy_m.value_or(NAN);
    const double position = result.predicted_position_accuracy_m.value_or(NAN);
    std::string camera = "-";
    if (result.camera) {
      const ResultCamera& c = *result.camera;
      camera =
          fmt::format("fx {:.3f} cx {:.3f}", c.parameters.at(0).value, c.parameters.at(2).value);
    }
    fmt::print(
        "{} poses {} true_rms_mm {:.4f} true_max_mm {:.4f} z_scale_ppm {:+.0f} "
        "predicted_robot_mm {:.4f} ratio_robot {:.2f} predicted_position_mm {:.4f} "
        "ratio_position {:.2f} verdict {} camera {}\n",
        path, t.poses, 1e3 * t.position_rms_m, 1e3 * t.position_max_m, t.z_scale_ppm, 1e3 * robot,
        robot / t.position_rms_m, 1e3 * position, position / t.position_rms_m,
        result.verdict ? result.verdict->code : "-", camera);
  }
}

}  // namespace
}  // namespace h4::host

int main(int argc, char** argv) {
  return h4::host::StudyMain("h4_true_accuracy", argc, argv, h4::host::Parse, h4::host::Run);
}
