// The simulation truth file; see truth_file.h.
#include "host/simulation/truth_file.h"


#include <fmt/core.h>

#include "common/formats/file_output.h"
#include "common/formats/format_error.h"
#include "common/formats/input_file.h"
#include "common/formats/number_text.h"
#include "common/formats/yaml_map.h"
#include "host/formats/robot_yaml.h"

namespace h4::host {
namespace {

std::string List3(const Eigen::Vector3d& v, const std::string& field) {
  return "[" + FormatDouble(v[0], field) + ", " + FormatDouble(v[1], field) + ", " +
         FormatDouble(v[2], field) + "]";
}

}  // namespace

std::string FormatTruthYaml(const SimulationTruth& truth) {
  const RigidTransform X_B31C = truth.robot.X_B31C();
  std::string text = FormatRobotYaml(truth.robot.Description(), "true");
  text += "simulation:  # the truth behind a simulated dataset (h4cal simulate)\n";
  text += std::string("  truth_model: \"") + ToString(truth.robot.truth_model()) + "\"\n";
  text += fmt::format("  robot_seed: {}\n", truth.robot_seed);
  text += fmt::format("  dataset_seed: {}\n", truth.dataset_seed);
  text += "  X_B31C:  # true camera pose in B31, the frame of Model 31\n";
  text += "    translation: " + List3(X_B31C.translation(), "X_B31C.translation") + "\n";
  text += "    rpy: " + List3(X_B31C.rpy(), "X_B31C.rpy") + "\n";
  text += "  noise:  # one sigma per axis\n";
  text += "    sigma_t: " + FormatDouble(truth.noise.sigma_t, "noise.sigma_t") + "  # m\n";
  text += "    sigma_r: " + FormatDouble(truth.noise.sigma_r, "noise.sigma_r") + "  # rad\n";
  text += "    sigma_q: " + FormatDouble(truth.noise.sigma_q, "noise.sigma_q") + "  # rad\n";
  return text;
}

void WriteTruthYaml(const std::string& path, const SimulationTruth& truth) {
  WriteFileAtomically(path, FormatTruthYaml(truth));
}

SimulationTruth ParseTruthYaml(const std::string& text, const std::string& source_name) {
  SimulationTruth truth;
  truth.robot = SimulatedRobot::FromDescription(ParseRobotYaml(text, source_name));
  const YamlMap root(LoadYaml(text, source_name), source_name, "", 0);
  const YamlMap simulation = root.Map("simulation");
  const std::string model = simulation.String("truth_model");
  const std::optional<ModelKind> kind = ParseModelKind(model);
  if (!kind) simulation.Fail("truth_model", "expected \"12\" or \"31\", got \"" + model + "\"");
  if (kind == ModelKind::k31 && !truth.robot.model31) {
    simulation.Fail("truth_model", "\"31\" needs a model31 block holding the true geometry");
  }
  if (kind == ModelKind::k12) truth.robot.model31.reset();
  truth.robot_seed = static_cast<uint64_t>(simulation.Int("robot_seed"));
  truth.dataset_seed = static_cast<uint64_t>(simulation.Int("dataset_seed"));
  const YamlMap noise = simulation.Map("noise");
  truth.noise.sigma_t = noise.Double("sigma_t");
  truth.noise.sigma_r = noise.Double("sigma_r");
  truth.noise.sigma_q = noise.Double("sigma_q");
  return truth;
}

SimulationTruth ReadTruthYaml(const std::string& path) {
  return ParseTruthYaml(ReadDataFile(path), path);
}

}  // namespace h4::host
