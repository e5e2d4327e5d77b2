// Loading the robot of fk / ik / validate from --result or --robot; see robot_source.h.
#include "host/cli/robot_source.h"

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

}  // namespace h4::host::cli
