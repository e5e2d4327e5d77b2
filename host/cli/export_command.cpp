// `h4cal export`: the identified parameters for the robot's controller, in the robot.yaml
// keys of common/formats/README.md (the control law reads model12: h, arm, forearm, R, d, alpha, q0
// and the assembly signs). A Model 31 result exports its own model31: block (the model12 block the
// format requires then comes from the a priori --robot). A result whose verdict is not good is
// exported with a warning and exit 3.
// Each identified model has its own base frame B (the paper fits the camera's placement X_BC
// with the model): loading another model moves B, and what was taught in base coordinates
// must be re-registered. With --previous (the result the controller ran before) export
// prints the transform between the two base frames, which the fixed camera ties together.
#include <memory>
#include <stdexcept>

#include <Eigen/Geometry>
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "common/cli/command_line.h"
#include "common/cli/shared_options.h"
#include "common/cli/subcommand.h"
#include "common/formats/file_output.h"
#include "common/units.h"
#include "host/cli/commands.h"
#include "host/formats/identification_result.h"
#include "host/formats/robot_yaml.h"
#include "host/identification/identified_robot.h"
#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4::host::cli {
namespace {

struct ExportOptions {
  std::string result_path;
  std::string robot_path;
  std::string out_path;
  std::string previous_path;  ///< the result the controller ran before, for the frame change
};

// The change of base frame from the previous result's B (B_prev) to this one's (B_new), each
// as its control law commands poses (CameraInPlanFrame): the camera C is the same physical
// frame in both, so X_BnewBprev = X_BnewC * inv(X_BprevC).
std::string ReRegistrationNote(const IdentificationResult& result, const std::string& path,
                               const std::optional<RobotDescription>& apriori,
                               const ExportOptions& options) {
  const std::string model = ModelLabel(result.model);
  if (options.previous_path.empty()) {
    return fmt::format(
        "work taught in base coordinates (fixtures, taught points) under the controller's "
        "previous model must be re-registered: {} has its own base frame. Give --previous "
        "RESULT (the result exported before) for the transform between the two.",
        model);
  }
  const IdentificationResult previous = ReadIdentificationResult(options.previous_path);
  if (!apriori && (result.model == ModelKind::k31 || previous.model == ModelKind::k31)) {
    throw std::invalid_argument(
        "--previous with a Model 31 result needs --robot robot.yaml: a Model 31 control law "
        "maps B to its base frame B31 with the a priori model's nominal transform");
  }
  // Without --robot both are Model 12 results, whose X_BC is in B already.
  const Model12Parameters m12 = apriori ? apriori->model12 : Model12Parameters{};
  const RigidTransform X_BnewBprev =
      CameraInPlanFrame(result, m12) * CameraInPlanFrame(previous, m12).inverse();
  const Eigen::Vector3d p_mm = X_BnewBprev.translation() * 1e3;
  const Eigen::Vector3d rpy = X_BnewBprev.rpy();
  const double angle_deg =
      DegreesFromRadians(Eigen::AngleAxisd(X_BnewBprev.rotation()).angle());
  return fmt::format(
      "base frame change from {} ({}) to {} ({}): a point taught at p in the previous base "
      "frame is at R p + t in this one, t = ({:.3f}, {:.3f}, {:.3f}) mm, R = rpy ({:.4f}, "
      "{:.4f}, {:.4f}) deg ({:.4f} deg in all). Re-register work taught in base coordinates "
      "with it; a point taught by jogging is better recomputed from its recorded joints "
      "(h4cal fk --result {}).",
      ModelLabel(previous.model), options.previous_path, model, path, p_mm[0], p_mm[1], p_mm[2],
      DegreesFromRadians(rpy[0]), DegreesFromRadians(rpy[1]), DegreesFromRadians(rpy[2]),
      angle_deg, path);
}

// A result the verdict does not call good is written (the user may want it) but not
// silently: the verdict and its advice are repeated, and the exit is 3 as identify's was.
int WarnUnlessGood(const IdentificationResult& result, const std::string& path) {
  if (!result.verdict || result.verdict->code == "good") return h4::cli::kExitSuccess;
  spdlog::warn("{}: its verdict is {}, not good: {} Export the result whose verdict is good.", path,
               result.verdict->code, result.verdict->text);
  return h4::cli::kExitNothingUsable;
}

int Run(const ExportOptions& options) {
  RequireOutputIsNotAnInput({"--out", options.out_path},
                            {{"--result", options.result_path},
                             {"--robot", options.robot_path},
                             {"--previous", options.previous_path}});
  const IdentificationResult result = ReadIdentificationResult(options.result_path);
  std::optional<RobotDescription> apriori;
  if (!options.robot_path.empty()) apriori = ReadRobotYaml(options.robot_path);
  RobotDescription out;
  if (apriori) out = *apriori;
  const Assembly assembly = apriori ? apriori->assembly : Assembly{};
  const IdentifiedRobot robot = RebuildFromResult(result, assembly);
  out.assembly = assembly;
  out.X_BC = robot.X_BC;
  out.X_TE = robot.X_TE;
  std::string header;
  if (result.model == ModelKind::k12) {
    out.model12 = dynamic_cast<const Model12&>(*robot.model).model12_parameters();
    out.model31.reset();
    header = "# h4cal export: identified Model 12 parameters of " + options.result_path +
             " for the control law (robot.yaml keys; X_BC, X_TE in B)\n";
  } else {
    if (!apriori) {
      throw std::invalid_argument(options.result_path +
                                  ": a Model 31 export needs --robot robot.yaml (the a priori "
                                  "model12 block the robot.yaml format requires)");
    }
    out.model31 = dynamic_cast<const Model31&>(*robot.model).model31_parameters();
    header = "# h4cal export: identified Model 31 parameters of " + options.result_path +
             " in the model31 block (model12 is the a priori of " + options.robot_path +
             "; X_BC is the camera in B31, the base frame of Model 31)\n";
  }
  const std::string frame_note = ReRegistrationNote(result, options.result_path, apriori, options);
  header += "# " + frame_note + "\n";
  WriteFileAtomically(options.out_path, header + FormatRobotYaml(out, "identified"));
  spdlog::info("wrote the Model {} controller parameters to {}", ToString(result.model),
               options.out_path);
  spdlog::info("{}", frame_note);
  return WarnUnlessGood(result, options.result_path);
}

}  // namespace

void DeclareExportCommand(CLI::App* command) {
  const auto options = std::make_shared<ExportOptions>();
  h4::cli::AddResultOption(command, &options->result_path)->required();
  h4::cli::AddRobotOption(command, &options->robot_path,
                          "A priori robot.yaml: assembly signs (and the model12 block of a Model "
                          "31 export)");
  h4::cli::AddOutOption(command, &options->out_path, "controller.yaml to write");
  h4::cli::AddInputFileOption(command, "--previous", &options->previous_path,
                              "Result JSON the controller ran before (an earlier export's): "
                              "prints the change of base frame between the two models, for "
                              "re-registering work taught in base coordinates");
  h4::cli::RunWhenParsedForExitCode(command, options, Run);
}

}  // namespace h4::host::cli
