// The truth file of a simulation: the true robot in the robot.yaml layout of common/formats/README.md
// (so it can be passed as --robot to evaluate with the true geometry) plus a `simulation:`
// block, which robot.yaml readers ignore, with the truth model, the camera in B31, the
// seeds and the noise settings.
#pragma once

#include <cstdint>
#include <string>

#include "host/simulation/dataset_simulator.h"
#include "host/simulation/true_robot.h"

namespace h4::host {

struct SimulationTruth {
  SimulatedRobot robot;
  NoiseOptions noise;
  uint64_t robot_seed = 0;    ///< PerturbationOptions::seed the robot was drawn with
  uint64_t dataset_seed = 0;  ///< DatasetOptions::seed of the dataset
};

/// YAML text: FormatRobotYaml(robot.Description()) followed by
///   simulation:
///     truth_model: "12" | "31"
///     robot_seed: N
///     dataset_seed: N
///     X_B31C: {translation: [..], rpy: [..]}   # true camera in B31 (Model 31's answer)
///     noise: {sigma_t: m, sigma_r: rad, sigma_q: rad}
std::string FormatTruthYaml(const SimulationTruth& truth);
void WriteTruthYaml(const std::string& path, const SimulationTruth& truth);

/// Reads it back; throws FormatError (file, line, field) when malformed, e.g. truth_model
/// "31" without a model31 block.
SimulationTruth ParseTruthYaml(const std::string& text, const std::string& source_name);
SimulationTruth ReadTruthYaml(const std::string& path);

}  // namespace h4::host
