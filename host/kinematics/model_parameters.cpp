// See model_parameters.h.
#include "host/kinematics/model_parameters.h"

#include <algorithm>
#include <array>
#include <string>

namespace h4 {
namespace {

constexpr ParameterKind kPositive = ParameterKind::kPositiveLength;
constexpr ParameterKind kLength = ParameterKind::kLength;
constexpr ParameterKind kAngle = ParameterKind::kAngle;

constexpr std::array<ModelParameter, 13> kModel12 = {{
    {"h", kPositive},
    {"arm", kPositive},
    {"forearm", kPositive},
    {"R", kPositive},
    {"d", kLength},
    {"alpha1", kAngle},
    {"alpha2", kAngle},
    {"alpha3", kAngle},
    {"alpha4", kAngle},
    {"q01", kAngle},
    {"q02", kAngle},
    {"q03", kAngle},
    {"q04", kAngle},
}};

constexpr std::array<ModelParameter, 31> kModel31 = {{
    {"x2", kLength},         {"y2", kLength},         {"z2", kLength},
    {"x3", kLength},         {"y3", kLength},         {"z3", kLength},
    {"x4", kLength},         {"y4", kLength},         {"z4", kLength},
    {"psi1", kAngle},        {"psi2", kAngle},        {"psi3", kAngle},
    {"psi4", kAngle},        {"beta1", kAngle},       {"beta2", kAngle},
    {"beta3", kAngle},       {"beta4", kAngle},       {"q01", kAngle},
    {"q02", kAngle},         {"q03", kAngle},         {"q04", kAngle},
    {"arm1", kPositive},     {"arm2", kPositive},     {"arm3", kPositive},
    {"arm4", kPositive},     {"forearm1", kPositive}, {"forearm2", kPositive},
    {"forearm3", kPositive}, {"forearm4", kPositive}, {"h", kPositive},
    {"d", kLength},
}};

std::optional<ParameterKind> KindInTables(std::string_view name) {
  for (std::span<const ModelParameter> table :
       {std::span<const ModelParameter>(kModel12), std::span<const ModelParameter>(kModel31)}) {
    const auto it = std::find_if(table.begin(), table.end(),
                                 [name](const ModelParameter& p) { return p.name == name; });
    if (it != table.end()) return it->kind;
  }
  return std::nullopt;
}

}  // namespace

std::string_view UnitOf(ParameterKind kind) { return kind == kAngle ? "rad" : "m"; }

std::span<const ModelParameter> Model12ParameterTable() { return kModel12; }

std::span<const ModelParameter> Model31ParameterTable() { return kModel31; }

std::vector<std::string> ParameterNamesOf(std::span<const ModelParameter> table) {
  std::vector<std::string> names;
  for (const ModelParameter& p : table) names.emplace_back(p.name);
  return names;
}

std::optional<ParameterKind> ModelParameterKind(std::string_view name) {
  if (const std::optional<ParameterKind> kind = KindInTables(name)) return kind;
  // A family's name is its first member's without the index: alpha -> alpha1, q0 -> q01.
  return KindInTables(std::string(name) + "1");
}

bool IsPositiveLengthParameter(std::string_view name) {
  return ModelParameterKind(name) == kPositive;
}

bool IsModelAngleParameter(std::string_view name) { return ModelParameterKind(name) == kAngle; }

bool IsAngleParameter(std::string_view name) {
  if (IsModelAngleParameter(name)) return true;
  const size_t dot = name.find('.');  // X_BC.rx ... X_TE.rz
  return dot != std::string_view::npos && name.substr(dot).starts_with(".r");
}

}  // namespace h4
