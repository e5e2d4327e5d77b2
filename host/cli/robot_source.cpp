// Loading the robot of fk / ik / validate from --result or --robot; see robot_source.h.
#include "host/cli/robot_source.h"

#include <cmath>

#include <fmt/format.h>

#include "common/cli/shared_options.h"
#include "host/formats/identification_result.h"
#include "host/formats/robot_yaml.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host::cli {

void AddRobotSourceOptions(CLI::App* command, RobotSourceOptions* options) {
  auto* result = h4::cli::AddResultOption(command, &options->result_path,
                                          "Identification result JSON (h4cal identify --out)");
  // As in export and check: beside --result, --robot gives the assembly signs.
  auto* robot = h4::cli::AddRobotOption(
      command, &options->robot_path,
      "A priori robot.yaml: alone, its Model 12 (or a Model 31 export's model31) with X_BC and "
      "X_TE; with --result, the assembly signs (bar, elbow) that go with it (default: the "
      "standard H4 assembly)");
  // The old spelling of --robot beside --result (scripts keep running; not in --help).
  h4::cli::AddInputFileOption(command, "--assembly-from", &options->assembly_robot_path, "")
      ->needs(result)
      ->excludes(robot)
      ->group("");
}

IdentifiedRobot LoadRobot(const RobotSourceOptions& options, std::string* description) {
  if (options.result_path.empty() && options.robot_path.empty()) {
    throw std::invalid_argument("give --result (with --robot for its assembly signs) or --robot");
  }
  if (!options.result_path.empty()) {
    const IdentificationResult result = ReadIdentificationResult(options.result_path);
    const std::string& assembly_path =
        options.robot_path.empty() ? options.assembly_robot_path : options.robot_path;
    const Assembly assembly =
        assembly_path.empty() ? Assembly{} : ReadRobotYaml(assembly_path).assembly;
    if (description) *description = ModelLabel(result.model) + " result " + options.result_path;
    return RebuildFromResult(result, assembly);
  }
  const RobotDescription robot = ReadRobotYaml(options.robot_path);
  if (robot.model31) {
    // A Model 31 export (h4cal export): its model31 block is the robot, and its X_BC the
    // camera in B31; the model12 block beside it is only the a priori the format requires.
    if (description) *description = "Model 31 of " + options.robot_path;
    return IdentifiedRobot{std::make_unique<Model31>(*robot.model31, robot.assembly), robot.X_BC,
                           robot.X_TE};
  }
  if (description) *description = "a priori Model 12 of " + options.robot_path;
  return IdentifiedRobot{std::make_unique<Model12>(robot.model12, robot.assembly), robot.X_BC,
                         robot.X_TE};
}

namespace {

double AprioriOf(const IdentificationResult& result, const std::string& name) {
  for (const ResultParameter& p : result.parameters) {
    if (p.name == name) return p.apriori;
  }
  throw std::invalid_argument("the Model 31 result has no parameter " + name);
}

// NominalX_B31B of the a priori a Model 31 result was identified from: its a priori values
// are that Model 12's nominal Model 31, (x_i, y_i) = R (cos alpha_1 - cos alpha_i,
// sin alpha_1 - sin alpha_i) with psi_i = alpha_i; R from the leg with the longest base.
RigidTransform AprioriX_B31B(const IdentificationResult& result) {
  Model12Parameters m12;
  const double alpha1 = AprioriOf(result, "psi1");
  double longest = 0.0;
  for (int i = 2; i <= 4; ++i) {
    const double alpha = AprioriOf(result, fmt::format("psi{}", i));
    const Eigen::Vector2d unit(std::cos(alpha1) - std::cos(alpha),
                               std::sin(alpha1) - std::sin(alpha));
    if (unit.norm() <= longest) continue;
    longest = unit.norm();
    m12.R = Eigen::Vector2d(AprioriOf(result, fmt::format("x{}", i)),
                            AprioriOf(result, fmt::format("y{}", i)))
                .norm() /
            longest;
  }
  m12.alpha[0] = alpha1;
  m12.d = AprioriOf(result, "d");
  return NominalX_B31B(m12);
}

}  // namespace

EePose RobotInB::ToModelFrame(const EePose& x_B) const {
  return X_B31B ? EePoseInB31(x_B, *X_B31B) : x_B;
}

EePose RobotInB::FromModelFrame(const EePose& x_M) const {
  return X_B31B ? EePoseInB31(x_M, X_B31B->inverse()) : x_M;
}

RobotInB LoadRobotInB(const RobotSourceOptions& options, std::string* description) {
  RobotInB out{LoadRobot(options, description), std::nullopt};
  if (out.robot.model->kind() != ModelKind::k31) return out;
  const std::string& beside =
      options.robot_path.empty() ? options.assembly_robot_path : options.robot_path;
  if (options.result_path.empty()) {  // a Model 31 export: its model12 block is the a priori
    out.X_B31B = NominalX_B31B(ReadRobotYaml(options.robot_path).model12);
  } else if (!beside.empty()) {
    out.X_B31B = NominalX_B31B(ReadRobotYaml(beside).model12);
  } else {
    out.X_B31B = AprioriX_B31B(ReadIdentificationResult(options.result_path));
  }
  return out;
}

}  // namespace h4::host::cli
