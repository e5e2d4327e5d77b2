// The verdict section of the report; see report_verdict.h.
#include "host/report/report_verdict.h"

#include <algorithm>
#include <iterator>
#include <utility>
#include <vector>

#include <spdlog/fmt/fmt.h>

#include "common/text/markup_escape.h"
#include "common/units.h"

namespace h4::host {
namespace {

// A verdict figure as a technician reads it: its name in words, its value in mm, deg, % or
// a plain number. The result keeps the SI key (common/formats/README.md), shown on hover.
struct ReadableFigure {
  std::string label;
  std::string value;
};

ReadableFigure Readable(const std::string& key, double value) {
  const auto count = [&](const char* label) {
    return ReadableFigure{label, fmt::format("{:.0f}", value)};
  };
  if (key == "poses_given") return count("poses in the dataset");
  if (key == "poses_in_fit") return count("poses in the fit");
  if (key == "poses_rejected") return count("poses rejected as outliers");
  if (key == "poses_out_of_reach") return count("poses out of the model's reach");
  if (key == "free_parameters") return count("parameters identified");
  if (key == "dof") return count("degrees of freedom of the fit");
  if (key == "chi2") return {"chi-square of the fit", fmt::format("{:.1f}", value)};
  if (key == "reduced_chi2") {
    return {"chi-square / degrees of freedom (1: the misfit the camera's noise predicts)",
            fmt::format("{:.3g}", value)};
  }
  if (key == "chi2_upper_tail_probability") {
    return {"probability of so large a chi-square from the camera's noise alone",
            value < 1e-6 ? std::string("below 1e-6") : fmt::format("{:.3g}", value)};
  }
  if (key == "condition_number") {
    return {"condition number of the scaled identification Jacobian", fmt::format("{:.3g}", value)};
  }
  if (key == "position_misfit_m") {
    return {"board position misfit, RMS over the poses in the fit (mm)",
            fmt::format("{:.4f}", value * 1e3)};
  }
  if (key == "unexplained_position_misfit_m") {
    return {"misfit beyond what the camera's noise explains (mm)",
            fmt::format("{:.4f}", value * 1e3)};
  }
  if (key == "largest_relative_length_change") {
    return {"largest length change from the a priori robot (%)",
            fmt::format("{:.2f}", value * 100.0)};
  }
  if (key == "largest_angle_change_rad") {
    return {"largest angle change from the a priori robot (deg)",
            fmt::format("{:.3f}", DegreesFromRadians(value))};
  }
  if (key == "dataset_sigmas") {
    return {"pose covariance from the dataset's sigma columns",
            value != 0.0 ? "yes" : "no (defaults)"};
  }
  return {key, fmt::format("{:.4g}", value)};  // a figure this report does not know yet
}

// The figures in the order the verdict reads them (the poses, the fit against the noise, the
// misfit, the departures from the a priori, the conditioning), then any other; the file
// keeps them in its own (alphabetical) order.
std::vector<std::pair<std::string, double>> InReadingOrder(
    const std::vector<std::pair<std::string, double>>& figures) {
  static const std::vector<std::string> kOrder = {"poses_given",
                                                  "poses_in_fit",
                                                  "poses_rejected",
                                                  "poses_out_of_reach",
                                                  "free_parameters",
                                                  "dataset_sigmas",
                                                  "chi2",
                                                  "dof",
                                                  "reduced_chi2",
                                                  "chi2_upper_tail_probability",
                                                  "position_misfit_m",
                                                  "unexplained_position_misfit_m",
                                                  "largest_relative_length_change",
                                                  "largest_angle_change_rad",
                                                  "condition_number"};
  std::vector<std::pair<std::string, double>> ordered;
  for (const std::string& key : kOrder) {
    for (const auto& figure : figures) {
      if (figure.first == key) ordered.push_back(figure);
    }
  }
  for (const auto& figure : figures) {
    if (std::find(kOrder.begin(), kOrder.end(), figure.first) == kOrder.end()) {
      ordered.push_back(figure);
    }
  }
  return ordered;
}

std::string FiguresTable(const ResultVerdict& verdict) {
  std::string t;
  t += "<table class=\"verdict-figures\">\n<tr><th>what the verdict was decided from</th>"
       "<th>value</th></tr>\n";
  for (const auto& [key, value] : InReadingOrder(verdict.figures)) {
    const ReadableFigure figure = Readable(key, value);
    t += "<tr><th title=\"" + MarkupEscape(key) + "\">" + MarkupEscape(figure.label) + "</th><td>" +
         MarkupEscape(figure.value) + "</td></tr>\n";
  }
  return t + "</table>\n";
}

std::string RejectedTable(const IdentificationResult& r) {
  if (r.rejected_details.empty()) return "<p>No pose rejected.</p>\n";
  std::string t;
  t += "<table class=\"rejected\">\n<tr><th>rejected pose</th><th>score</th><th>why</th></tr>\n";
  for (const RejectedPose& pose : r.rejected_details) {
    fmt::format_to(std::back_inserter(t), "<tr><th>{}</th><td>{:.3g}</td><td>{}</td></tr>\n",
                   pose.pose_id, pose.score, MarkupEscape(pose.reason));
  }
  return t + "</table>\n";
}

std::string Provenance(const IdentificationResult& r) {
  if (!r.provenance)
    return "<p>This result does not record which h4cal made it, when, or from what.</p>\n";
  std::string inputs;
  for (const std::string& input : r.provenance->inputs) {
    inputs += (inputs.empty() ? "" : ", ") + ("<code>" + MarkupEscape(input) + "</code>");
  }
  return fmt::format("<p>Made by h4cal {} on {} from {}.</p>\n",
                     MarkupEscape(r.provenance->h4cal_version),
                     MarkupEscape(r.provenance->date_utc), inputs);
}

std::string HeldOutFigures(const IdentificationResult& r) {
  if (!r.cross_validation) return "";
  const CrossValidationFigures& cv = *r.cross_validation;
  return fmt::format(
      "<p class=\"cross-validation\">Held out ({}-fold cross-validation: each of the {} poses "
      "predicted by the model fitted without it): board position {:.4f} mm RMS, rotation "
      "{:.4f} deg RMS, normalised chi-square / dof {:.3g}.</p>\n",
      cv.folds, cv.poses, cv.position_rms_m * 1e3, DegreesFromRadians(cv.rotation_rms_rad),
      cv.reduced_chi2);
}

std::string ResultVerdictBlock(const IdentificationResult& r) {
  std::string t;
  t += "<h3>" + ModelLabel(r.model) + "</h3>\n";
  if (!r.verdict) {
    t += "<p class=\"note\">No verdict recorded in this result (written by an older "
         "h4cal): identify again.</p>\n";
  } else {
    const bool good = r.verdict->code == "good";
    fmt::format_to(std::back_inserter(t),
                   "<p class=\"{}\"><strong>{}</strong>: {}</p>\n"
                   "{}",
                   (good ? "verdict-good" : "verdict-bad"), MarkupEscape(r.verdict->code),
                   MarkupEscape(r.verdict->text), FiguresTable(*r.verdict));
  }
  return t + HeldOutFigures(r) + RejectedTable(r) + Provenance(r);
}

}  // namespace

std::string VerdictSection(const ValidationInputs& in) {
  std::string html;
  for (const auto* result : {&in.result12, &in.result31}) {
    if (*result) html += ResultVerdictBlock(**result);
  }
  return html.empty() ? "<p>No identification result given.</p>\n" : html;
}

}  // namespace h4::host
