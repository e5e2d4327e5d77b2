// The coverage study: does the uncertainty h4cal reports hold? Over many simulated
// paper-protocol campaigns (81-pose grid, 0.2 mm / 0.03 deg camera noise, 10 poses held
// out with their truth), each identified with the default commands (`identify --model 12`,
// and on Model 31 robots `--model 31 --from` it), it compares
//  - the predicted positioning accuracy (1 sigma from the covariance, scaled by the reduced
//    chi-square when above 1) with the actual error of the identified robot on the held-out
//    poses (board position predicted from the true joints against the true board pose);
//  - the parameters' 95 % intervals (value +- 1.96 sigma) with the true values, over the
//    parameters the truth defines in the result's own frame: Model 12's kinematic
//    parameters but d (fixed), and Model 31's lengths (arm_i, forearm_i, h), which do not
//    depend on the base-frame choices the identifiability analysis fixes;
//  - the accuracy map's predicted 1-sigma positioning error (host/validation/accuracy_map.h)
//    with the actual error of the true robot driven through the identified model's inverse
//    kinematics to each map pose (the pose it reaches by forward kinematics, against the
//    commanded one, both after the best rigid registration of the base frame), where the
//    result's model is the truth's (the same kind of base frame);
//  - and counts the verdicts (a campaign the model describes should be "good").
// Usage: h4_coverage_study [--campaigns N (100)] [--first-seed S (1)] [--map-in-model-frame
// (the map and actual errors without the rigid registration of the base frame)]; prints a
// Markdown table (docs/results.md#uncertainty-that-holds).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "host/identification/identification.h"
#include "host/identification/identified_robot.h"
#include "host/kinematics/forward_kinematics.h"
#include "host/kinematics/paper_robot.h"
#include "host/kinematics/pose_plan.h"
#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"
#include "host/validation/accuracy_map.h"

namespace h4::host {
namespace {

struct Tally {
  int campaigns = 0;
  double predicted_sq = 0.0;  ///< sum over campaigns of predicted accuracy^2
  double actual_sq = 0.0;     ///< sum over campaigns of the held-out truth error^2 (RMS)
  int intervals = 0, covered = 0;
  double map_predicted_sq = 0.0;  ///< sum over map poses of predicted position sigma^2
  double map_actual_sq = 0.0;     ///< sum over the same poses of the actual error^2
  int map_poses = 0;
  std::map<std::string, int> verdicts;
};

struct Campaign {
  SimulatedRobot truth;
  SimulatedDataset data;
};

Campaign MakeCampaign(TrueGeometry geometry, uint64_t seed) {
  PerturbationOptions perturbation;
  perturbation.seed = seed;
  Campaign c{MakeTrueRobot(PaperAprioriRobot(), geometry, perturbation), {}};
  DatasetOptions options;
  options.seed = seed;
  c.data = SimulateDataset(c.truth, GridPosePlan(), options);
  return c;
}

// RMS board position error of the identified robot on the held-out poses: predicted from
// the true joints, against the true board pose. Model 31 results live in B31, like the
// truth's joints and board poses (the board pose X_CT does not depend on the base frame).
double HeldOutTruthError(const IdentificationResult& result, const Campaign& c) {
  const IdentifiedRobot robot = RebuildFromResult(result, c.truth.assembly);
  double sum = 0.0;
  int n = 0;
  for (size_t j = 0; j < c.data.rows.size(); ++j) {
    if (c.data.rows[j].set != PoseSet::kValid) continue;
    const SimulatedPose& pose = c.data.truth[j];
    const auto X_CT = PredictBoardPose(*robot.model, robot.X_BC, robot.X_TE, pose.q);
    if (!X_CT) continue;
    sum += (X_CT->translation() - pose.X_CT.translation()).squaredNorm();
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

// The true value of each parameter the study checks, by result name.
std::map<std::string, double> TrueParameters(const SimulatedRobot& truth, ModelKind model) {
  std::map<std::string, double> values;
  if (model == ModelKind::k12) {
    const Model12Parameters& p = truth.model12;
    values = {{"h", p.h}, {"arm", p.arm}, {"forearm", p.forearm}, {"R", p.R}};
    for (int i = 0; i < 4; ++i) {
      values[fmt::format("alpha{}", i + 1)] = p.alpha[static_cast<size_t>(i)];
      values[fmt::format("q0{}", i + 1)] = p.q0[static_cast<size_t>(i)];
    }
    return values;
  }
  const Model31Parameters p = truth.TrueModel31();
  values["h"] = p.h;
  for (int i = 0; i < 4; ++i) {
    values[fmt::format("arm{}", i + 1)] = p.arm[static_cast<size_t>(i)];
    values[fmt::format("forearm{}", i + 1)] = p.forearm[static_cast<size_t>(i)];
  }
  return values;
}

double WrappedDifference(const std::string& name, double a, double b) {
  double d = a - b;
  if (name.rfind("alpha", 0) == 0 || name.rfind("q0", 0) == 0) {
    d = std::remainder(d, 2.0 * std::numbers::pi);
  }
  return d;
}

// --map-in-model-frame: the map and the actual errors without the rigid registration.
bool g_register_base_frame = true;

// The accuracy map of the result against the truth: each map pose commanded through the
// identified model's IK, reached by the true robot's FK. Only where the result's model is
// the truth's, so that both poses are in the same base frame.
void CountAccuracyMap(const IdentificationResult& r, const Campaign& c, Tally* tally) {
  const std::unique_ptr<KinematicModel> truth = c.truth.MakeModel();
  if (truth->kind() != r.model) return;
  AccuracyMapOptions map_options;
  map_options.register_base_frame = g_register_base_frame;
  const std::optional<AccuracyMap> map = AccuracyMapOfResult(r, c.truth.assembly, map_options);
  if (!map) return;
  const IdentifiedRobot identified = RebuildFromResult(r, c.truth.assembly);
  std::vector<EePose> commanded, reached;
  double predicted_sq = 0.0;
  for (const AccuracyMapPoint& point : map->points) {
    const IkResult ik = identified.model->InverseKinematics(point.x);
    const FkResult fk = ForwardKinematics(*truth, ik.q, point.x);
    if (!ik.ok() || !fk.ok()) continue;
    commanded.push_back(point.x);
    reached.push_back(fk.x);
    predicted_sq += point.position_sigma_m * point.position_sigma_m;
  }
  // The actual errors registered as the map's are (accuracy_map.h), with the exact rotation:
  // the identified frame may be turned by degrees from the truth's.
  if (g_register_base_frame) {
    for (const Eigen::Vector4d& e : ResidualAfterRigidRegistration(commanded, reached)) {
      tally->map_actual_sq += e.head<3>().squaredNorm();
    }
  } else {
    for (size_t k = 0; k < commanded.size(); ++k) {
      tally->map_actual_sq += (reached[k] - commanded[k]).head<3>().squaredNorm();
    }
  }
  tally->map_predicted_sq += predicted_sq;
  tally->map_poses += static_cast<int>(commanded.size());
}

void Count(const IdentificationOutcome& out, const Campaign& c, Tally* tally) {
  const IdentificationResult& r = out.result;
  ++tally->campaigns;
  ++tally->verdicts[r.verdict ? r.verdict->code : "none"];
  const double actual = HeldOutTruthError(r, c);
  tally->actual_sq += actual * actual;
  const double predicted = r.predicted_position_accuracy_m.value_or(0.0);
  tally->predicted_sq += predicted * predicted;
  CountAccuracyMap(r, c, tally);
  // A Model 31 robot has no true Model 12 parameters: only the accuracy is compared.
  if (r.model == ModelKind::k12 && c.truth.model31) return;
  for (const auto& [name, value] : TrueParameters(c.truth, r.model)) {
    const ResultParameter* p = r.Find(name);
    if (p == nullptr || p->fixed || !p->std) continue;
    ++tally->intervals;
    if (std::abs(WrappedDifference(name, p->value, value)) <= 1.96 * *p->std) ++tally->covered;
  }
}

void PrintRow(const std::string& truth, const std::string& model, const Tally& t) {
  const double predicted = std::sqrt(t.predicted_sq / t.campaigns);
  const double actual = std::sqrt(t.actual_sq / t.campaigns);
  std::string verdicts;
  for (const auto& [code, n] : t.verdicts) {
    fmt::format_to(std::back_inserter(verdicts), "{}{} {}", verdicts.empty() ? "" : ", ", code, n);
  }
  std::string coverage = "n/a (no true Model 12)";
  if (t.intervals > 0) {
    coverage = fmt::format("{:.1f} % ({})", 100.0 * t.covered / t.intervals, t.intervals);
  }
  std::string map = "n/a (other base frame)";
  if (t.map_poses > 0) {
    const double map_predicted = std::sqrt(t.map_predicted_sq / t.map_poses);
    const double map_actual = std::sqrt(t.map_actual_sq / t.map_poses);
    map = fmt::format("{:.4f} / {:.4f} = {:.2f}", map_predicted * 1e3, map_actual * 1e3,
                      map_predicted / map_actual);
  }
  fmt::print("| {} | {} | {} | {:.4f} | {:.4f} | {:.2f} | {} | {} | {} |\n", truth, model,
             t.campaigns, predicted * 1e3, actual * 1e3, predicted / actual, coverage, map,
             verdicts);
}

int Run(int campaigns, uint64_t first_seed) {
  Tally m12, m31_from_12, m12_on_31;
  for (uint64_t seed = first_seed; seed < first_seed + static_cast<uint64_t>(campaigns); ++seed) {
    const Campaign c12 = MakeCampaign(TrueGeometry::kPerturbedModel12, seed);
    Count(IdentifyRobot(PaperAprioriRobot(), ModelKind::k12, c12.data.rows, {}), c12, &m12);
    const Campaign c31 = MakeCampaign(TrueGeometry::kPerturbedModel31, seed);
    const IdentificationOutcome out12 =
        IdentifyRobot(PaperAprioriRobot(), ModelKind::k12, c31.data.rows, {});
    Count(out12, c31, &m12_on_31);
    Count(IdentifyModel31FromModel12(PaperAprioriRobot(), out12.result, c31.data.rows, {}), c31,
          &m31_from_12);
    fmt::print(stderr, "\rcampaign {}", static_cast<unsigned long long>(seed));
  }
  fmt::print(stderr, "\n");
  fmt::print(
      "| truth | identified with | campaigns | predicted accuracy, RMS (mm) | actual held-out "
      "error, RMS (mm) | predicted / actual | 95 % intervals holding the truth (intervals) | "
      "accuracy map: predicted / actual positioning error, RMS (mm) | verdicts |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  PrintRow("Model 12", "Model 12", m12);
  PrintRow("Model 31", "Model 31 --from Model 12", m31_from_12);
  PrintRow("Model 31", "Model 12", m12_on_31);
  return 0;
}

}  // namespace
}  // namespace h4::host

int main(int argc, char** argv) {
  int campaigns = 100;
  uint64_t first_seed = 1;
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--map-in-model-frame") {
      h4::host::g_register_base_frame = false;
      --i;
    } else if (i + 1 >= argc) {
      fmt::print(stderr, "{} needs a value\n", flag);
      return 1;
    } else if (flag == "--campaigns") {
      campaigns = std::atoi(argv[i + 1]);
    } else if (flag == "--first-seed") {
      first_seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else {
      fmt::print(stderr, "usage: {} [--campaigns N] [--first-seed S] [--map-in-model-frame]\n",
                 argv[0]);
      return 1;
    }
  }
  if (campaigns < 1) {
    fmt::print(stderr, "--campaigns must be at least 1\n");
    return 1;
  }
  return h4::host::Run(campaigns, first_seed);
}
