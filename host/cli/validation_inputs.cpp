// Loading the validation inputs and the text summary (see validation_inputs.h).
#include "host/cli/validation_inputs.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "common/formats/robot_yaml.h"

namespace h4::host::cli {
namespace {

namespace fs = std::filesystem;

// `explicit_path`, else `name` in the sim dir when it exists there (or when required).
std::string Resolve(const std::string& explicit_path, const std::string& sim_dir,
                    const std::string& name, bool required, const std::string& option) {
  if (!explicit_path.empty()) return explicit_path;
  if (!sim_dir.empty()) {
    const fs::path candidate = fs::path(sim_dir) / name;
    if (fs::exists(candidate) || required) return candidate.string();
  }
  if (required) throw std::invalid_argument(option + " is required (or --sim-dir)");
  return "";
}

void CheckExists(const std::string& path) {
  if (!path.empty() && !fs::exists(path)) throw std::invalid_argument(path + ": no such file");
}

std::optional<IdentificationResult> ReadResult(const std::string& path,
                                               const std::string& expected_model,
                                               const std::string& option) {
  if (path.empty()) return std::nullopt;
  CheckExists(path);
  IdentificationResult result = ReadIdentificationResult(path);
  if (result.model != expected_model) {
    throw std::invalid_argument(fmt::format("{}: a Model {} result given to {} (expected Model {})",
                                            path, result.model, option, expected_model));
  }
  return result;
}

}  // namespace

void AddValidationFileOptions(CLI::App* command, ValidationFileOptions* o) {
  command->add_option("--sim-dir", o->sim_dir,
                      "Folder written by `h4cal simulate` (+ result12.json, result31.json): "
                      "default for every file below");
  command->add_option("--robot", o->robot_path, "A priori robot.yaml");
  command->add_option("--data", o->data_path, "Paired dataset CSV");
  command->add_option("--result12", o->result12_path, "Model 12 identification result JSON");
  command->add_option("--result31", o->result31_path, "Model 31 identification result JSON");
  command->add_option("--truth", o->truth_path,
                      "truth.yaml of a simulation: the true robot for the square path");
  command->add_option("--straightness", o->straightness_paths,
                      "Joints CSVs logged along a straight ruler, one per direction");
  command->add_option("--square-mm", o->square_mm, "Side of the square path, mm")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

ValidationInputs LoadValidationInputs(const ValidationFileOptions& o) {
  ValidationInputs in;
  const std::string robot = Resolve(o.robot_path, o.sim_dir, "robot.yaml", true, "--robot");
  const std::string data = Resolve(o.data_path, o.sim_dir, "dataset.csv", true, "--data");
  const std::string r12 = Resolve(o.result12_path, o.sim_dir, "result12.json", false, "");
  const std::string r31 = Resolve(o.result31_path, o.sim_dir, "result31.json", false, "");
  const std::string truth = Resolve(o.truth_path, o.sim_dir, "truth.yaml", false, "");
  for (const auto& path : {robot, data, truth}) CheckExists(path);
  in.apriori = ReadRobotYaml(robot);
  in.rows = ReadDatasetCsv(data);
  in.dataset_name = data;
  in.result12 = ReadResult(r12, "12", "--result12");
  in.result31 = ReadResult(r31, "31", "--result31");
  if (!in.result12 && !in.result31) {
    throw std::invalid_argument("give an identification result: --result12 and/or --result31");
  }
  if (!truth.empty()) in.truth = ReadTruthYaml(truth);
  std::vector<std::string> runs = o.straightness_paths;
  if (runs.empty() && !o.sim_dir.empty()) {
    for (int k = 1; fs::exists(fs::path(o.sim_dir) / fmt::format("straightness_{}.csv", k)); ++k) {
      runs.push_back((fs::path(o.sim_dir) / fmt::format("straightness_{}.csv", k)).string());
    }
  }
  for (const auto& path : runs) {
    CheckExists(path);
    in.straightness.push_back(ReadJointsCsv(path));
    if (in.straightness.back().size() < 3) {
      throw std::invalid_argument(path + ": a straightness run needs at least 3 readings");
    }
  }
  in.square.side = o.square_mm * 1e-3;
  return in;
}

std::string FormatValidationText(const ValidationReport& report) {
  std::ostringstream t;
  t << fmt::format("Table 3: joint residuals on {} held-out poses (rad, measured - model)\n",
                   report.heldout_ids.size());
  for (const auto& v : report.models) {
    const auto& r = v.heldout;
    t << fmt::format("  {:<10} mean {:9.1e} {:9.1e} {:9.1e} {:9.1e}\n", v.label, r.mean[0],
                     r.mean[1], r.mean[2], r.mean[3]);
    t << fmt::format("  {:<10} RMS  {:9.1e} {:9.1e} {:9.1e} {:9.1e}\n", "", r.rms[0], r.rms[1],
                     r.rms[2], r.rms[3]);
  }
  t << fmt::format("Positioning error: a priori, every pose: {:.2f} mm, {:.4f} rad (mean)\n",
                   report.apriori_all.position_mean * 1e3, report.apriori_all.theta_mean);
  for (const auto& v : report.models) {
    t << fmt::format("  {:<10} held out: {:.3f} mm, {:.5f} rad (mean)\n", v.label,
                     v.positioning.position_mean * 1e3, v.positioning.theta_mean);
  }
  if (!report.models.front().straightness.empty()) {
    t << "Table 4: straightness (m)\n";
    for (size_t m = 0; m < report.models.size(); ++m) {
      t << fmt::format("  {:<10}", report.models[m].label);
      for (size_t r = 0; r < report.models[m].straightness.size(); ++r) {
        t << fmt::format("  dir {}: {:.1e}", r + 1,
                         report.models[m].straightness[r].fit.rms_distance);
        if (m > 0) t << fmt::format(" ({:.0f} %)", report.StraightnessImprovementPercent(m, r));
      }
      t << "\n";
    }
  }
  for (const auto& v : report.models) {
    if (!v.square) continue;
    t << fmt::format(
        "Square, {} controller: side RMS {:.2f} {:.2f} {:.2f} {:.2f} mm, shape {:.2f} mm, "
        "mean |reached - commanded| {:.2f} mm\n",
        v.label, v.square->sides[0].rms * 1e3, v.square->sides[1].rms * 1e3,
        v.square->sides[2].rms * 1e3, v.square->sides[3].rms * 1e3, v.square->shape_rms * 1e3,
        v.square->mean_position_error * 1e3);
  }
  t << (report.prior.ok ? fmt::format("4-DoF check: rotation axis spread {:.3f} deg\n",
                                      report.prior.axis_spread_deg)
                        : "4-DoF check: " + report.prior.message + "\n");
  for (const auto& note : report.notes) t << "note: " << note << "\n";
  return t.str();
}

}  // namespace h4::host::cli
