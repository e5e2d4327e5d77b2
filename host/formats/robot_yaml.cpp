// Robot description YAML; see robot_yaml.h.
#include "host/formats/robot_yaml.h"

#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "common/formats/csv_table.h"
#include "common/formats/file_kind.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"
#include "common/formats/pose_columns.h"
#include "common/formats/yaml_map.h"
#include "host/kinematics/model_parameters.h"

namespace h4 {
namespace {

// The bounds of common/formats/README.md#robot-description-yaml---robot, the result JSON's (no part
// of an H4 lies kMaxRobotSize_m from its base, no angle needs more than a turn): a value past
// them is a typing mistake or a damaged file, and 1e154 made `identify` loop on a Jacobian
// of inf and NaN and `analyze` print NaN. Each check names the file, line and field.
constexpr double kTurn = 2.0 * std::numbers::pi;

void CheckBound(const YamlMap& map, const std::string& key, std::optional<size_t> index,
                double value, ParameterKind kind) {
  const auto fail = [&](const std::string& what) {
    if (index) map.FailElement(key, *index, what);
    map.Fail(key, what);
  };
  const std::string field = map.FieldOf(key);
  switch (kind) {
    case ParameterKind::kPositiveLength:
      if (!(value > 0.0)) fail("expected a positive length, got " + FormatDouble(value, field));
      [[fallthrough]];
    case ParameterKind::kLength:
      if (!(std::abs(value) <= kMaxRobotSize_m)) {
        fail("expected a length within " + FormatDouble(kMaxRobotSize_m, field) + " m, got " +
             FormatDouble(value, field));
      }
      break;
    case ParameterKind::kAngle:
      if (!(std::abs(value) <= kTurn)) {
        fail("expected an angle within one turn (|a| <= 2 pi rad), got " +
             FormatDouble(value, field));
      }
      break;
  }
}

double Bounded(const YamlMap& map, const std::string& key, ParameterKind kind) {
  const double value = map.Double(key);
  CheckBound(map, key, std::nullopt, value, kind);
  return value;
}

std::vector<double> BoundedList(const YamlMap& map, const std::string& key, size_t count,
                                ParameterKind kind) {
  const std::vector<double> values = map.Doubles(key, count);
  for (size_t i = 0; i < count; ++i) CheckBound(map, key, i, values[i], kind);
  return values;
}

std::array<double, 4> Four(const YamlMap& map, const std::string& key, ParameterKind kind) {
  const std::vector<double> values = BoundedList(map, key, 4, kind);
  return {values[0], values[1], values[2], values[3]};
}

// A model parameter (or robot.yaml's list of four, "psi" for psi1..psi4), bounded as its kind
// in the models' table says (host/kinematics/model_parameters.h).
double ModelValue(const YamlMap& map, const std::string& key) {
  return Bounded(map, key, ModelParameterKind(key).value());
}

std::array<double, 4> FourModelValues(const YamlMap& map, const std::string& key) {
  return Four(map, key, ModelParameterKind(key).value());
}

std::array<int, 4> Signs(const YamlMap& map, const std::string& key) {
  const std::vector<int64_t> values = map.Ints(key, 4);
  std::array<int, 4> out{};
  for (size_t i = 0; i < 4; ++i) {
    if (values[i] != 1 && values[i] != -1) {
      map.FailElement(key, i, fmt::format("expected 1 or -1, got {}", values[i]));
    }
    out[i] = static_cast<int>(values[i]);
  }
  return out;
}

RigidTransform ReadTransform(const YamlMap& map) {
  map.RejectUnknownKeys({"translation", "rpy"});
  const std::vector<double> t = BoundedList(map, "translation", 3, ParameterKind::kLength);
  const std::vector<double> rpy = BoundedList(map, "rpy", 3, ParameterKind::kAngle);
  return RigidTransform::FromTranslationRpy({t[0], t[1], t[2]}, {rpy[0], rpy[1], rpy[2]});
}

Model31Parameters ReadModel31(const YamlMap& map) {
  map.RejectUnknownKeys({"x2", "y2", "z2", "x3", "y3", "z3", "x4", "y4", "z4", "psi", "beta", "q0",
                         "arm", "forearm", "h", "d"});
  Model31Parameters m31;
  for (size_t j = 0; j < 3; ++j) {
    const std::string n = fmt::format("{}", j + 2);
    m31.P[j] = Eigen::Vector3d(ModelValue(map, "x" + n), ModelValue(map, "y" + n),
                               ModelValue(map, "z" + n));
  }
  m31.psi = FourModelValues(map, "psi");
  m31.beta = FourModelValues(map, "beta");
  m31.q0 = FourModelValues(map, "q0");
  m31.arm = FourModelValues(map, "arm");
  m31.forearm = FourModelValues(map, "forearm");
  m31.h = ModelValue(map, "h");
  m31.d = ModelValue(map, "d");
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
  return fmt::format("[{}]", fmt::join(values, ", "));
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
  robot.model12.h = ModelValue(m12, "h");
  robot.model12.arm = ModelValue(m12, "arm");
  robot.model12.forearm = ModelValue(m12, "forearm");
  robot.model12.R = ModelValue(m12, "R");
  robot.model12.d = ModelValue(m12, "d");
  robot.model12.alpha = FourModelValues(m12, "alpha");
  robot.model12.q0 = FourModelValues(m12, "q0");
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
      const std::string n = fmt::format("{}", j + 2);
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
