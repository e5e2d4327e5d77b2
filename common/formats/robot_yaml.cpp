// Robot description YAML; see robot_yaml.h.
#include "common/formats/robot_yaml.h"

#include "common/formats/csv_table.h"
#include "common/formats/file_kind.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"
#include "common/formats/yaml_map.h"

namespace h4 {
namespace {

std::array<double, 4> Four(const YamlMap& map, const std::string& key, bool positive) {
  const std::vector<double> values = map.Doubles(key, 4);
  std::array<double, 4> out{};
  for (size_t i = 0; i < 4; ++i) {
    if (positive && !(values[i] > 0.0)) {
      map.FailElement(key, i, "expected a positive length, got " + FormatDouble(values[i], key));
    }
    out[i] = values[i];
  }
  return out;
}

std::array<int, 4> Signs(const YamlMap& map, const std::string& key) {
  const std::vector<int64_t> values = map.Ints(key, 4);
  std::array<int, 4> out{};
  for (size_t i = 0; i < 4; ++i) {
    if (values[i] != 1 && values[i] != -1) {
      map.FailElement(key, i, "expected 1 or -1, got " + std::to_string(values[i]));
    }
    out[i] = static_cast<int>(values[i]);
  }
  return out;
}

RigidTransform ReadTransform(const YamlMap& map) {
  map.RejectUnknownKeys({"translation", "rpy"});
  const std::vector<double> t = map.Doubles("translation", 3);
  const std::vector<double> rpy = map.Doubles("rpy", 3);
  return RigidTransform::FromTranslationRpy({t[0], t[1], t[2]}, {rpy[0], rpy[1], rpy[2]});
}

Model31Parameters ReadModel31(const YamlMap& map) {
  map.RejectUnknownKeys({"x2", "y2", "z2", "x3", "y3", "z3", "x4", "y4", "z4", "psi", "beta", "q0",
                         "arm", "forearm", "h", "d"});
  Model31Parameters m31;
  for (size_t j = 0; j < 3; ++j) {
    const std::string n = std::to_string(j + 2);
    m31.P[j] = Eigen::Vector3d(map.Double("x" + n), map.Double("y" + n), map.Double("z" + n));
  }
  m31.psi = Four(map, "psi", false);
  m31.beta = Four(map, "beta", false);
  m31.q0 = Four(map, "q0", false);
  m31.arm = Four(map, "arm", true);
  m31.forearm = Four(map, "forearm", true);
  m31.h = map.PositiveDouble("h");
  m31.d = map.Double("d");
  return m31;
}

std::string List(const double* values, size_t n, const std::string& field) {
  std::string text = "[";
  for (size_t i = 0; i < n; ++i) text += (i ? ", " : "") + FormatDouble(values[i], field);
  return text + "]";
}

std::string List(const std::array<double, 4>& values, const std::string& field) {
  return List(values.data(), 4, field);
}

std::string Signs(const std::array<int, 4>& values) {
  std::string text = "[";
  for (size_t i = 0; i < 4; ++i) text += (i ? ", " : "") + std::to_string(values[i]);
  return text + "]";
}

std::string Transform(const std::string& name, const std::string& comment,
                      const RigidTransform& X) {
  const Eigen::Vector3d rpy = X.rpy();
  return name + ":  # " + comment +
         "\n  translation: " + List(X.translation().data(), 3, name + ".translation") +
         "\n  rpy: " + List(rpy.data(), 3, name + ".rpy") + "\n";
}

}  // namespace

RobotDescription ParseRobotYaml(const std::string& text, const std::string& source_name) {
  if (const FileKind kind = GuessFileKind(text);
      kind == FileKind::kDatasetCsv || kind == FileKind::kOtherCsv) {
    throw FormatError(source_name, 1, "",
                      std::string("this looks like ") + DescribeFileKind(kind) +
                          ", not a robot.yaml (were --robot and --data swapped?)");
  }
  const YamlMap root(LoadYaml(text, source_name), source_name, "", 0);
  root.RejectCaseVariants({"model12", "model31", "assembly", "X_BC", "X_TE"});
  RobotDescription robot;
  const YamlMap m12 = root.Map("model12");
  m12.RejectUnknownKeys({"h", "arm", "forearm", "R", "d", "alpha", "q0"});
  robot.model12.h = m12.PositiveDouble("h");
  robot.model12.arm = m12.PositiveDouble("arm");
  robot.model12.forearm = m12.PositiveDouble("forearm");
  robot.model12.R = m12.PositiveDouble("R");
  robot.model12.d = m12.Double("d");
  robot.model12.alpha = Four(m12, "alpha", false);
  robot.model12.q0 = Four(m12, "q0", false);
  if (root.Has("assembly")) {
    const YamlMap assembly = root.Map("assembly");
    assembly.RejectUnknownKeys({"bar", "elbow"});
    if (assembly.Has("bar")) robot.assembly.bar = Signs(assembly, "bar");
    if (assembly.Has("elbow")) robot.assembly.elbow = Signs(assembly, "elbow");
  }
  robot.X_BC = ReadTransform(root.Map("X_BC"));
  robot.X_TE = ReadTransform(root.Map("X_TE"));
  if (root.Has("model31")) robot.model31 = ReadModel31(root.Map("model31"));
  return robot;
}

RobotDescription ReadRobotYaml(const std::string& path) {
  return ParseRobotYaml(ReadTextFile(path), path);
}

std::string FormatRobotYaml(const RobotDescription& robot, const std::string& kind) {
  const Model12Parameters& m12 = robot.model12;
  std::string text =
      "# " + kind +
      " description of the H4 and of the measurement set-up (SI units: m, rad)\n"
      "# names: common/README.md; layout: common/formats/README.md \"Robot description\"\n";
  text += "model12:\n  h: " + FormatDouble(m12.h, "model12.h") +
          "\n  arm: " + FormatDouble(m12.arm, "model12.arm") +
          "\n  forearm: " + FormatDouble(m12.forearm, "model12.forearm") +
          "\n  R: " + FormatDouble(m12.R, "model12.R") +
          "\n  d: " + FormatDouble(m12.d, "model12.d") +
          "\n  alpha: " + List(m12.alpha, "model12.alpha") +
          "\n  q0: " + List(m12.q0, "model12.q0") + "\n";
  text += "assembly:\n  bar: " + Signs(robot.assembly.bar) +
          "  # s_i\n  elbow: " + Signs(robot.assembly.elbow) + "  # eps_i\n";
  text += Transform("X_BC", kind + " camera pose in base", robot.X_BC);
  text += Transform("X_TE", kind + " end-effector pose in board frame", robot.X_TE);
  if (robot.model31) {
    const Model31Parameters& m31 = *robot.model31;
    text += "model31:  # overrides the nominal Model 31 derived from model12\n";
    for (size_t j = 0; j < 3; ++j) {
      const std::string n = std::to_string(j + 2);
      text += "  x" + n + ": " + FormatDouble(m31.P[j].x(), "model31.x" + n) + "\n";
      text += "  y" + n + ": " + FormatDouble(m31.P[j].y(), "model31.y" + n) + "\n";
      text += "  z" + n + ": " + FormatDouble(m31.P[j].z(), "model31.z" + n) + "\n";
    }
    text += "  psi: " + List(m31.psi, "model31.psi") + "\n";
    text += "  beta: " + List(m31.beta, "model31.beta") + "\n";
    text += "  q0: " + List(m31.q0, "model31.q0") + "\n";
    text += "  arm: " + List(m31.arm, "model31.arm") + "\n";
    text += "  forearm: " + List(m31.forearm, "model31.forearm") + "\n";
    text += "  h: " + FormatDouble(m31.h, "model31.h") + "\n";
    text += "  d: " + FormatDouble(m31.d, "model31.d") + "\n";
  }
  return text;
}

void WriteRobotYaml(const std::string& path, const RobotDescription& robot) {
  WriteTextFile(path, FormatRobotYaml(robot));
}

}  // namespace h4
