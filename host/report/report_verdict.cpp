// The verdict section of the report; see report_verdict.h.
#include "host/report/report_verdict.h"

#include <sstream>

#include <spdlog/fmt/fmt.h>

#include "common/text/markup_escape.h"
#include "common/units.h"

namespace h4::host {
namespace {

std::string FiguresTable(const ResultVerdict& verdict) {
  std::ostringstream t;
  t << "<table class=\"verdict-figures\">\n<tr><th>figure</th><th>value</th></tr>\n";
  for (const auto& [name, value] : verdict.figures) {
    t << "<tr><th>" << MarkupEscape(name) << "</th><td>" << fmt::format("{:.4g}", value)
      << "</td></tr>\n";
  }
  return t.str() + "</table>\n";
}

std::string RejectedTable(const IdentificationResult& r) {
  if (r.rejected_details.empty()) return "<p>No pose rejected.</p>\n";
  std::ostringstream t;
  t << "<table class=\"rejected\">\n<tr><th>rejected pose</th><th>score</th><th>why</th></tr>\n";
  for (const RejectedPose& pose : r.rejected_details) {
    t << "<tr><th>" << pose.pose_id << "</th><td>" << fmt::format("{:.3g}", pose.score)
      << "</td><td>" << MarkupEscape(pose.reason) << "</td></tr>\n";
  }
  return t.str() + "</table>\n";
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
  std::ostringstream t;
  t << "<h3>" << ModelLabel(r.model) << "</h3>\n";
  if (!r.verdict) {
    t << "<p class=\"note\">No verdict recorded in this result (written by an older "
         "h4cal): identify again.</p>\n";
  } else {
    const bool good = r.verdict->code == "good";
    t << "<p class=\"" << (good ? "verdict-good" : "verdict-bad") << "\"><strong>"
      << MarkupEscape(r.verdict->code) << "</strong>: " << MarkupEscape(r.verdict->text) << "</p>\n"
      << FiguresTable(*r.verdict);
  }
  return t.str() + HeldOutFigures(r) + RejectedTable(r) + Provenance(r);
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
