// The robot description YAML (common/formats/README.md#robot-description-yaml---robot, `--robot`):
// the a priori Model 12 parameters, assembly signs, a priori X_BC and X_TE, and an optional model31
// block with the Model 31 names of common/README.md. SI units (m, rad).
#pragma once

#include <string>

#include "host/kinematics/robot_description.h"

namespace h4 {

/// Reads robot.yaml. Required: model12 (h, arm, forearm, R, d, alpha[4], q0[4]), X_BC and
/// X_TE (translation[3], rpy[3]). Optional: assembly (bar[4], elbow[4], each +-1; default
/// Assembly{}), model31 (x2 y2 z2 x3 y3 z3 x4 y4 z4, psi[4], beta[4], q0[4], arm[4],
/// forearm[4], h, d: all keys when the block is there). Lengths h, arm, forearm, R must
/// be positive. Other top-level keys are ignored (common/formats/README.md allows them) unless they
/// differ from a known one only by letter case; an unknown key inside one of the blocks
/// above is an error. Throws FormatError with file, line and field ("model12.alpha[2]")
/// on any malformed value.
RobotDescription ParseRobotYaml(const std::string& text, const std::string& source_name);
RobotDescription ReadRobotYaml(const std::string& path);

/// Writes the same layout under a comment header, shortest round-trip numbers; the
/// rotations of X_BC and X_TE as roll-pitch-yaw. `kind` says in the comments what the
/// values are: "a priori" (a robot.yaml), "identified" (h4cal export), "true" (a truth).
std::string FormatRobotYaml(const RobotDescription& robot, const std::string& kind = "a priori");
void WriteRobotYaml(const std::string& path, const RobotDescription& robot);

}  // namespace h4
