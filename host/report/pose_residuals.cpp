// The per-pose residual table and CSV; see pose_residuals.h.
#include "host/report/pose_residuals.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include <spdlog/fmt/fmt.h>

#include "common/text/markup_escape.h"
#include "common/units.h"

namespace h4::host {
namespace {

using Residuals = std::array<double, 4>;

// A model's residuals by pose id (every dataset row it reaches).
std::map<int64_t, Residuals> ByPose(const ModelValidation& model) {
  std::map<int64_t, Residuals> out;
  for (size_t k = 0; k < model.all.pose_ids.size() && k < model.all.residuals.size(); ++k) {
    out[model.all.pose_ids[k]] = model.all.residuals[k];
  }
  return out;
}

// "a priori" -> "apriori", "Model 12" -> "model12": a CSV column prefix.
std::string ColumnPrefix(const std::string& label) {
  std::string prefix;
  for (char c : label) {
    if (c != ' ') prefix += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return prefix;
}

double LargestDeg(const Residuals& r) {
  double largest = 0.0;
  for (double q : r) largest = std::max(largest, std::abs(q));
  return DegreesFromRadians(largest);
}

std::set<int64_t> AllPoses(const std::vector<std::map<int64_t, Residuals>>& models) {
  std::set<int64_t> ids;
  for (const auto& model : models) {
    for (const auto& entry : model) ids.insert(entry.first);
  }
  return ids;
}

}  // namespace

std::string PoseResidualsCsv(const ValidationReport& report) {
  std::vector<std::map<int64_t, Residuals>> models;
  std::string csv = "pose_id,evaluated";
  for (const ModelValidation& model : report.models) {
    models.push_back(ByPose(model));
    const std::string prefix = ColumnPrefix(model.label);
    for (int j = 1; j <= 4; ++j) csv += fmt::format(",{}_q{}_deg", prefix, j);
  }
  csv += "\n";
  const std::set<int64_t> evaluated(report.heldout_ids.begin(), report.heldout_ids.end());
  for (int64_t id : AllPoses(models)) {
    csv += fmt::format("{},{}", id, evaluated.count(id) ? 1 : 0);
    for (const auto& model : models) {
      const auto it = model.find(id);
      for (int j = 0; j < 4; ++j) {
        csv += it == model.end() ? std::string(",")
                                 : fmt::format(",{:.6f}", DegreesFromRadians(it->second[j]));
      }
    }
    csv += "\n";
  }
  return csv;
}

std::string PoseResidualsTable(const ValidationReport& report, size_t rows) {
  if (report.models.empty()) return "";
  std::vector<std::map<int64_t, Residuals>> models;
  for (const ModelValidation& model : report.models) models.push_back(ByPose(model));
  std::vector<std::pair<double, int64_t>> worst;  // by the last model's largest residual
  for (const auto& [id, r] : models.back()) worst.push_back({LargestDeg(r), id});
  std::sort(worst.rbegin(), worst.rend());
  if (worst.size() > rows) worst.resize(rows);
  std::string html = fmt::format(
      "<p>The {} poses {} misfits most: each model's largest joint residual (measured minus "
      "model, deg) at the pose; every pose and joint in <code>residuals.csv</code> beside "
      "this page.</p>\n<table class=\"pose-residuals\">\n<tr><th>pose</th>",
      worst.size(), MarkupEscape(report.models.back().label));
  for (const ModelValidation& model : report.models) {
    html += "<th>" + MarkupEscape(model.label) + "</th>";
  }
  html += "</tr>\n";
  for (const auto& [largest, id] : worst) {
    html += fmt::format("<tr><th>{}</th>", id);
    for (const auto& model : models) {
      const auto it = model.find(id);
      html += it == model.end() ? "<td>out of reach</td>"
                                : fmt::format("<td>{:.4f}</td>", LargestDeg(it->second));
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

}  // namespace h4::host
