// The identification result JSON
// (common/formats/README.md#identification-result-json-h4cal-identify---out); see
// identification_result.h. Keys are written in the order common/formats/README.md lists them, then
// the extra keys of the solver's account.
#include "host/formats/identification_result.h"

#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/formats/csv_table.h"
#include "common/formats/format_error.h"
#include "common/formats/number_text.h"
#include "host/formats/json_fields.h"
#include "host/kinematics/model_parameters.h"

namespace h4 {
namespace {

constexpr double kPi = std::numbers::pi;

using Ordered = nlohmann::ordered_json;

// A value the kinematics can use: lengths positive, every position within kMaxRobotSize_m
// of the base, every angle within a turn. A result edited or damaged by hand is refused
// here, naming the field, instead of driving ik or the controller export.
void RequireSensibleValue(const JsonValue& field, const std::string& name, double value) {
  if (IsPositiveLengthParameter(name) && !(value > 0.0)) {
    field.Fail("expected a positive length for " + name + ", got " + FormatDouble(value, name));
  }
  if (IsModelAngleParameter(name) && std::abs(value) > 2.0 * kPi) {
    field.Fail("expected an angle within one turn (|" + name + "| <= 2 pi rad), got " +
               FormatDouble(value, name));
  }
  if (!IsModelAngleParameter(name) && std::abs(value) > kMaxRobotSize_m) {
    field.Fail("expected |" + name + "| <= " + FormatDouble(kMaxRobotSize_m, name) + " m, got " +
               FormatDouble(value, name));
  }
}

// A standard deviation no larger than the range its value may take (a turn for an angle,
// kMaxRobotSize_m for a length or position): anything larger says nothing of the robot,
// and 1e200 made every d^2 of `h4cal check` NaN, which no threshold flags.
void RequireSensibleStd(const JsonValue& field, const std::string& name, double std_dev) {
  const bool angle = IsAngleParameter(name);
  const double limit = angle ? 2.0 * kPi : kMaxRobotSize_m;
  if (!(std_dev <= limit)) {
    field.Fail("expected a standard deviation of " + name +
               " <= " + (angle ? std::string("2 pi rad") : FormatDouble(limit, name) + " m") +
               ", got " + FormatDouble(std_dev, name));
  }
}

RigidTransform ReadTransform(const JsonValue& value) {
  const std::vector<double> t = value["translation"].Numbers(3);
  for (size_t i = 0; i < 3; ++i) {
    if (std::abs(t[i]) > kMaxRobotSize_m) {
      value["translation"].At(i).Fail("expected a translation within " +
                                      FormatDouble(kMaxRobotSize_m, "translation") + " m");
    }
  }
  const std::vector<double> rpy = value["rpy"].Numbers(3);
  return RigidTransform::FromTranslationRpy({t[0], t[1], t[2]}, {rpy[0], rpy[1], rpy[2]});
}

std::array<double, 4> ReadRms(const JsonValue& value) {
  value.ArraySize(4);
  std::array<double, 4> rms{};
  for (size_t i = 0; i < 4; ++i) rms[i] = value.At(i).NonNegativeNumber();
  return rms;
}

std::optional<double> OptionalNumber(const JsonValue& root, const std::string& key) {
  return root.HasNonNull(key) ? root[key].NumberOrNull() : std::nullopt;
}

void ReadParameters(const JsonValue& list, IdentificationResult* result) {
  const size_t n = list.ArraySize();
  std::set<std::string> names;
  for (size_t i = 0; i < n; ++i) {
    const JsonValue entry = list.At(i);
    ResultParameter p;
    p.name = entry["name"].String();
    if (p.name.empty()) entry["name"].Fail("expected a parameter name, got an empty string");
    if (!names.insert(p.name).second) entry["name"].Fail("parameter '" + p.name + "' given twice");
    p.value = entry["value"].Number();
    RequireSensibleValue(entry["value"], p.name, p.value);
    p.apriori = entry["apriori"].Number();
    const std::string status = entry["status"].String();
    if (status != "identified" && status != "fixed") {
      entry["status"].Fail("expected \"identified\" or \"fixed\", got \"" + status + "\"");
    }
    p.fixed = status == "fixed";
    p.std = entry["std"].NumberOrNull();
    if (p.std && p.fixed) entry["std"].Fail("expected null for a fixed parameter");
    if (p.std && *p.std < 0.0) entry["std"].Fail("expected a non-negative standard deviation");
    if (p.std) RequireSensibleStd(entry["std"], p.name, *p.std);
    result->parameters.push_back(p);
  }
}

void ReadFixed(const JsonValue& list, IdentificationResult* result) {
  const size_t n = list.ArraySize();
  for (size_t i = 0; i < n; ++i) {
    const JsonValue entry = list.At(i);
    FixedParameter f{entry["name"].String(), entry["reason"].String()};
    const ResultParameter* p = result->Find(f.name);
    if (p == nullptr || !p->fixed) {
      entry["name"].Fail("expected the name of a parameter with status \"fixed\", got \"" + f.name +
                         "\"");
    }
    result->fixed.push_back(f);
  }
}

ResultVerdict ReadVerdict(const JsonValue& object) {
  ResultVerdict verdict{object["code"].String(), object["text"].String(), {}};
  if (object.HasNonNull("figures")) {
    const JsonValue figures = object["figures"];
    figures.RequireObject();
    for (const auto& item : figures.json().items()) {
      verdict.figures.emplace_back(item.key(), figures[item.key()].Number());
    }
  }
  return verdict;
}

// A non-negative number of at most `limit`.
double NonNegativeAtMost(const JsonValue& field, double limit, const char* what) {
  const double value = field.NonNegativeNumber();
  if (!(value <= limit)) field.Fail(std::string("expected ") + what);
  return value;
}

// The verdict, the rejected poses with their scores and the provenance: extra keys that
// results written before them lack.
void ReadJudgement(const JsonValue& root, IdentificationResult* result) {
  if (root.HasNonNull("verdict")) result->verdict = ReadVerdict(root["verdict"]);
  if (root.HasNonNull("rejected_details")) {
    const JsonValue list = root["rejected_details"];
    const size_t n = list.ArraySize();
    for (size_t i = 0; i < n; ++i) {
      const JsonValue entry = list.At(i);
      result->rejected_details.push_back(
          {entry["pose_id"].Integer(), entry["score"].Number(), entry["reason"].String()});
    }
  }
  if (root.HasNonNull("cross_validation")) {
    const JsonValue object = root["cross_validation"];
    result->cross_validation = CrossValidationFigures{
        static_cast<int>(object["folds"].Integer()), static_cast<int>(object["poses"].Integer()),
        object["position_rms_m"].NonNegativeNumber(),
        object["rotation_rms_rad"].NonNegativeNumber(), object["reduced_chi2"].NonNegativeNumber()};
  }
  if (root.HasNonNull("camera_error_floor")) {
    const JsonValue object = root["camera_error_floor"];
    result->camera_error_floor = CameraErrorFloor{
        NonNegativeAtMost(object["rotation_rad"], 2.0 * std::numbers::pi, "at most 2 pi rad"),
        NonNegativeAtMost(object["translation_m"], kMaxRobotSize_m, "at most 10 m")};
  }
  if (root.HasNonNull("provenance")) {
    const JsonValue object = root["provenance"];
    ResultProvenance provenance{object["h4cal_version"].String(), object["date_utc"].String(), {}};
    const JsonValue inputs = object["inputs"];
    const size_t n = inputs.ArraySize();
    for (size_t i = 0; i < n; ++i) provenance.inputs.push_back(inputs.At(i).String());
    result->provenance = provenance;
  }
}

// One sigma per parameter as the file gives it (0 without one).
Eigen::VectorXd StdOrZero(const IdentificationResult& result) {
  Eigen::VectorXd std_dev =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(result.parameters.size()));
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    std_dev[static_cast<Eigen::Index>(i)] = result.parameters[i].std.value_or(0.0);
  }
  return std_dev;
}

// A covariance agrees with the `std` keys: its diagonal is their square (a parameter without
// one has a zero row), it is symmetric and, as correlations, positive semi-definite.
void RequireConsistentCovariance(const JsonValue& field, const Eigen::MatrixXd& C,
                                 const Eigen::VectorXd& std_dev) {
  const Eigen::Index n = C.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double sigma = std_dev[i];
    const double diagonal = C(i, i);
    const bool agrees = sigma > 0.0
                            ? std::abs(std::sqrt(std::max(diagonal, 0.0)) - sigma) <= 1e-6 * sigma
                            : C.row(i).isZero(0.0) && C.col(i).isZero(0.0);
    if (!agrees) {
      field.At(static_cast<size_t>(i))
          .Fail(sigma > 0.0 ? "expected a diagonal equal to std^2 of the parameter"
                            : "expected zeros for a parameter without std");
    }
    for (Eigen::Index j = 0; j < i; ++j) {
      if (std::abs(C(i, j) - C(j, i)) > 1e-9 * std_dev[i] * std_dev[j]) {
        field.At(static_cast<size_t>(i))
            .At(static_cast<size_t>(j))
            .Fail("expected a symmetric matrix");
      }
    }
  }
  const Eigen::VectorXd inverse_std =
      std_dev.unaryExpr([](double s) { return s > 0.0 ? 1.0 / s : 0.0; });
  const Eigen::MatrixXd correlation = inverse_std.asDiagonal() * C * inverse_std.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(correlation, Eigen::EigenvaluesOnly);
  if (n > 0 && eigen.eigenvalues().minCoeff() < -1e-6) {
    field.Fail("expected a positive semi-definite covariance");
  }
}

// n rows of n numbers.
Eigen::MatrixXd ReadSquareMatrix(const JsonValue& field, size_t n) {
  field.ArraySize(n);
  Eigen::MatrixXd C(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) {
    const std::vector<double> row = field.At(i).Numbers(n);
    for (size_t j = 0; j < n; ++j) {
      C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = row[j];
    }
  }
  return C;
}

// `parameter_covariance`: n x n numbers in the order of `parameters`.
void ReadCovariance(const JsonValue& root, IdentificationResult* result) {
  if (!root.HasNonNull("parameter_covariance")) return;
  const JsonValue field = root["parameter_covariance"];
  const size_t n = result->parameters.size();
  const Eigen::MatrixXd C = ReadSquareMatrix(field, n);
  RequireConsistentCovariance(field, C, StdOrZero(*result));
  result->parameter_covariance = C;
}

// `parameter_covariance_camera_exact`: like `parameter_covariance`, which it needs beside
// it; knowing the camera exactly can only shrink a variance, so its diagonal is at most
// std^2 (zero where there is no std).
void ReadCameraExactCovariance(const JsonValue& root, IdentificationResult* result) {
  if (!root.HasNonNull("parameter_covariance_camera_exact")) return;
  const JsonValue field = root["parameter_covariance_camera_exact"];
  if (!result->parameter_covariance) field.Fail("expected parameter_covariance beside it");
  const Eigen::MatrixXd C = ReadSquareMatrix(field, result->parameters.size());
  const Eigen::VectorXd std_full = StdOrZero(*result);
  Eigen::VectorXd std_exact = C.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (Eigen::Index i = 0; i < C.rows(); ++i) {
    if (std_exact[i] > std_full[i] * (1.0 + 1e-6)) {
      field.At(static_cast<size_t>(i))
          .Fail("expected a variance at most std^2 (the camera known exactly cannot widen it)");
    }
  }
  RequireConsistentCovariance(field, C, std_exact);
  result->parameter_covariance_camera_exact = C;
}

void ReadExtras(const JsonValue& root, IdentificationResult* result) {
  if (root.HasNonNull("estimator")) result->estimator = root["estimator"].String();
  result->condition_number = OptionalNumber(root, "condition_number");
  result->valid_position_rms_m = OptionalNumber(root, "valid_position_rms_m");
  result->valid_rotation_rms_rad = OptionalNumber(root, "valid_rotation_rms_rad");
  result->predicted_position_accuracy_m = OptionalNumber(root, "predicted_position_accuracy_m");
  result->predicted_robot_accuracy_m = OptionalNumber(root, "predicted_robot_accuracy_m");
  if (root.HasNonNull("correlations")) {
    const JsonValue list = root["correlations"];
    const size_t n = list.ArraySize();
    for (size_t i = 0; i < n; ++i) {
      const JsonValue entry = list.At(i);
      CorrelatedPair pair{.a = entry["a"].String(),
                          .b = entry["b"].String(),
                          .correlation = entry["correlation"].Number()};
      if (pair.correlation < -1.0 || pair.correlation > 1.0) {
        entry["correlation"].Fail("expected a correlation in [-1, 1]");
      }
      result->correlations.push_back(pair);
    }
  }
  if (root.HasNonNull("log")) {
    const JsonValue list = root["log"];
    const size_t n = list.ArraySize();
    for (size_t i = 0; i < n; ++i) result->log.push_back(list.At(i).String());
  }
  ReadJudgement(root, result);
  ReadCovariance(root, result);
  ReadCameraExactCovariance(root, result);
  if (root.HasNonNull("camera")) result->camera = ReadResultCamera(root["camera"]);
}

Ordered Numbers(const double* values, size_t n, const std::string& field) {
  Ordered list = Ordered::array();
  for (size_t i = 0; i < n; ++i) {
    FormatDouble(values[i], field);  // throws on a non-finite value: JSON has no NaN
    list.push_back(values[i]);
  }
  return list;
}

Ordered Transform(const RigidTransform& X, const std::string& name) {
  const Eigen::Vector3d rpy = X.rpy();
  Ordered object = Ordered::object();
  object["translation"] = Numbers(X.translation().data(), 3, name + ".translation");
  object["rpy"] = Numbers(rpy.data(), 3, name + ".rpy");
  return object;
}

Ordered Number(double value, const std::string& field) {
  FormatDouble(value, field);  // throws on a non-finite value
  return value;
}

Ordered NumberOrNull(const std::optional<double>& value, const std::string& field) {
  return value ? Number(*value, field) : Ordered(nullptr);
}

void WriteJudgement(const IdentificationResult& result, Ordered* root) {
  if (result.verdict) {
    Ordered figures = Ordered::object();
    for (const auto& [name, value] : result.verdict->figures) {
      figures[name] = Number(value, "verdict.figures." + name);
    }
    (*root)["verdict"] = {
        {"code", result.verdict->code}, {"text", result.verdict->text}, {"figures", figures}};
  } else {
    (*root)["verdict"] = nullptr;
  }
  Ordered rejected = Ordered::array();
  for (const RejectedPose& pose : result.rejected_details) {
    rejected.push_back({{"pose_id", pose.pose_id},
                        {"score", Number(pose.score, "rejected_details.score")},
                        {"reason", pose.reason}});
  }
  (*root)["rejected_details"] = rejected;
  if (result.cross_validation) {
    const CrossValidationFigures& cv = *result.cross_validation;
    (*root)["cross_validation"] = {
        {"folds", cv.folds},
        {"poses", cv.poses},
        {"position_rms_m", Number(cv.position_rms_m, "cross_validation.position_rms_m")},
        {"rotation_rms_rad", Number(cv.rotation_rms_rad, "cross_validation.rotation_rms_rad")},
        {"reduced_chi2", Number(cv.reduced_chi2, "cross_validation.reduced_chi2")}};
  } else {
    (*root)["cross_validation"] = nullptr;
  }
  if (result.camera_error_floor) {
    const CameraErrorFloor& floor = *result.camera_error_floor;
    (*root)["camera_error_floor"] = {
        {"rotation_rad", Number(floor.rotation_rad, "camera_error_floor.rotation_rad")},
        {"translation_m", Number(floor.translation_m, "camera_error_floor.translation_m")}};
  } else {
    (*root)["camera_error_floor"] = nullptr;
  }
  if (result.provenance) {
    (*root)["provenance"] = {{"h4cal_version", result.provenance->h4cal_version},
                             {"date_utc", result.provenance->date_utc},
                             {"inputs", result.provenance->inputs}};
  } else {
    (*root)["provenance"] = nullptr;
  }
}

// A covariance over `parameters` (`key` names it in errors), or null.
Ordered Covariance(const IdentificationResult& result, const std::optional<Eigen::MatrixXd>& matrix,
                   const char* key) {
  if (!matrix) return nullptr;
  const Eigen::MatrixXd& C = *matrix;
  const Eigen::Index n = static_cast<Eigen::Index>(result.parameters.size());
  if (C.rows() != n || C.cols() != n) {
    throw std::invalid_argument(std::string(key) + ": expected one row and column per parameter");
  }
  Ordered rows = Ordered::array();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::VectorXd row = C.row(i).transpose();
    rows.push_back(Numbers(row.data(), static_cast<size_t>(n), key));
  }
  return rows;
}

}  // namespace

const ResultParameter* IdentificationResult::Find(const std::string& name) const {
  for (const ResultParameter& p : parameters) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

IdentificationResult ParseIdentificationResult(const std::string& text,
                                               const std::string& source_name) {
  const nlohmann::json document = LoadJson(text, source_name);
  const JsonValue root(document, source_name, "");
  root.RequireObject();
  IdentificationResult result;
  const std::string model = root["model"].String();
  const std::optional<ModelKind> kind = ParseModelKind(model);
  if (!kind) root["model"].Fail("expected \"12\" or \"31\", got \"" + model + "\"");
  result.model = *kind;
  ReadParameters(root["parameters"], &result);
  result.X_BC = ReadTransform(root["X_BC"]);
  result.X_TE = ReadTransform(root["X_TE"]);
  ReadFixed(root["fixed"], &result);
  result.calib_rms_rad = ReadRms(root["residuals"]["calib_rms_rad"]);
  result.valid_rms_rad = ReadRms(root["residuals"]["valid_rms_rad"]);
  const JsonValue poses = root["poses"];
  result.calib_poses = poses["calib"].Integers();
  result.valid_poses = poses["valid"].Integers();
  result.rejected_poses = poses["rejected"].Integers();
  ReadExtras(root, &result);
  return result;
}

IdentificationResult ReadIdentificationResult(const std::string& path) {
  return ParseIdentificationResult(ReadTextFile(path), path);
}

std::string FormatIdentificationResult(const IdentificationResult& result) {
  Ordered root = Ordered::object();
  root["model"] = ToString(result.model);
  Ordered parameters = Ordered::array();
  for (const ResultParameter& p : result.parameters) {
    Ordered entry = Ordered::object();
    entry["name"] = p.name;
    entry["value"] = Number(p.value, p.name);
    entry["apriori"] = Number(p.apriori, p.name + ".apriori");
    entry["std"] = p.fixed ? Ordered(nullptr) : NumberOrNull(p.std, p.name + ".std");
    entry["status"] = p.fixed ? "fixed" : "identified";
    parameters.push_back(entry);
  }
  root["parameters"] = parameters;
  root["X_BC"] = Transform(result.X_BC, "X_BC");
  root["X_TE"] = Transform(result.X_TE, "X_TE");
  Ordered fixed = Ordered::array();
  for (const FixedParameter& f : result.fixed)
    fixed.push_back({{"name", f.name}, {"reason", f.reason}});
  root["fixed"] = fixed;
  root["residuals"] = {
      {"calib_rms_rad", Numbers(result.calib_rms_rad.data(), 4, "residuals.calib_rms_rad")},
      {"valid_rms_rad", Numbers(result.valid_rms_rad.data(), 4, "residuals.valid_rms_rad")}};
  root["poses"] = {{"calib", result.calib_poses},
                   {"valid", result.valid_poses},
                   {"rejected", result.rejected_poses}};
  root["estimator"] = result.estimator;
  root["condition_number"] = NumberOrNull(result.condition_number, "condition_number");
  Ordered correlations = Ordered::array();
  for (const CorrelatedPair& pair : result.correlations) {
    correlations.push_back(
        {{"a", pair.a}, {"b", pair.b}, {"correlation", Number(pair.correlation, "correlation")}});
  }
  root["correlations"] = correlations;
  root["valid_position_rms_m"] = NumberOrNull(result.valid_position_rms_m, "valid_position_rms_m");
  root["valid_rotation_rms_rad"] =
      NumberOrNull(result.valid_rotation_rms_rad, "valid_rotation_rms_rad");
  root["predicted_position_accuracy_m"] =
      NumberOrNull(result.predicted_position_accuracy_m, "predicted_position_accuracy_m");
  root["predicted_robot_accuracy_m"] =
      NumberOrNull(result.predicted_robot_accuracy_m, "predicted_robot_accuracy_m");
  root["log"] = result.log;
  WriteJudgement(result, &root);
  root["parameter_covariance"] =
      Covariance(result, result.parameter_covariance, "parameter_covariance");
  root["parameter_covariance_camera_exact"] = Covariance(
      result, result.parameter_covariance_camera_exact, "parameter_covariance_camera_exact");
  root["camera"] = result.camera ? ResultCameraJson(*result.camera) : Ordered(nullptr);
  return root.dump(2) + "\n";
}

void WriteIdentificationResult(const std::string& path, const IdentificationResult& result) {
  const std::string text = FormatIdentificationResult(result);
  // Never a result its own reader refuses (issue 42, defect 9: the corner path wrote psi2 =
  // 7.6 rad and x2 = -55 km, which every later command refused): checked before writing.
  try {
    ParseIdentificationResult(text, path);
  } catch (const FormatError& e) {
    throw std::runtime_error(fmt::format(
        "{}: not written: the result cannot be trusted, h4cal's own reader refuses it ({})", path,
        e.what()));
  }
  WriteTextFile(path, text);
}

}  // namespace h4
