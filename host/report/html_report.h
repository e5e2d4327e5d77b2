// The calibration report: one self-contained HTML file (inline CSS and SVG figures, no
// script, nothing fetched) with the parameter tables, the identifiability summary, the
// analogues of the paper's Tables 2, 3 and 4, the square path (simulated and/or measured by
// the camera), the 4-DoF check, the camera model (report_camera.h) and the
// figures; on the paper scenario, the paper's published numbers beside ours.
#pragma once

#include <string>

#include "host/validation/validation.h"

namespace h4::host {

/// The ids of the page's sections, in order (tests check that each is present).
inline constexpr const char* kReportSections[] = {
    "verdict",      "summary",     "parameters",  "identifiability", "table2",
    "table3",       "positioning", "accuracy-map", "camera", "residuals",   "histograms",      "table4",
    "straightness", "square",      "square-plot", "four-dof",        "notes"};

/// The section of the square paths measured by the camera: present only when the report
/// has measured square runs (`--square-measured`).
inline constexpr const char* kMeasuredSquareSection = "square-measured-plot";

/// The page. `command` is shown as how the report was made. Throws std::runtime_error when a
/// figure cannot be drawn (no gnuplot): never a half report.
std::string FormatHtmlReport(const ValidationInputs& inputs, const ValidationReport& report,
                             const std::string& command);

/// Writes `dir`/report.html (creating dir), and accuracy_map_model12.csv /
/// accuracy_map_model31.csv for each identified model with an accuracy map
/// (common/formats/README.md); returns the page's path.
std::string WriteHtmlReport(const std::string& dir, const ValidationInputs& inputs,
                            const ValidationReport& report, const std::string& command);

}  // namespace h4::host
