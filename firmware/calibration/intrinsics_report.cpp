// The intrinsics calibration's report; see intrinsics_report.h.
#include "firmware/calibration/intrinsics_report.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "common/text/markup_escape.h"

namespace h4::cam {
namespace {

std::vector<std::string> DistortionCoefficientNames(IntrinsicsModel model) {
  switch (model) {
    case IntrinsicsModel::kRadTan:
      return {"k1", "k2", "p1", "p2", "k3"};
    case IntrinsicsModel::kRational:
      return {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};
    case IntrinsicsModel::kEquidistant:
      return {"k1", "k2", "k3", "k4"};
  }
  return {};
}

/// A number for SVG and HTML: fixed, `decimals` after the point.
std::string Decimal(double value, int decimals = 2) {
  return fmt::format("{:.{}f}", value, decimals);
}

/// One colour per view, hues spread around the wheel.
std::string ViewColour(size_t view, size_t views) {
  const double hue =
      360.0 * static_cast<double>(view) / static_cast<double>(std::max<size_t>(1, views));
  return "hsl(" + Decimal(hue, 0) + ",75%,42%)";
}

double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0;
  const size_t k = std::min(values.size() - 1,
                            static_cast<size_t>(fraction * static_cast<double>(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

double LargestOf(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

std::string SvgHeader(int width, int height) {
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
      "width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" "
      "font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      width, height);
}

std::string SvgText(double x, double y, const std::string& text, const char* anchor = "start") {
  return "<text x=\"" + Decimal(x) + "\" y=\"" + Decimal(y) + "\" text-anchor=\"" + anchor + "\">" +
         MarkupEscape(text) + "</text>\n";
}

std::string SvgFrame(double x, double y, double width, double height) {
  return "<rect x=\"" + Decimal(x) + "\" y=\"" + Decimal(y) + "\" width=\"" + Decimal(width) +
         "\" height=\"" + Decimal(height) + "\" fill=\"none\" stroke=\"black\"/>\n";
}

/// The plot area of one panel: data (x0..x1, y0..y1) onto the box (left, top, w, h), y up.
struct PlotBox {
  double left = 0, top = 0, width = 0, height = 0;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  double X(double x) const { return left + width * (x - x0) / (x1 - x0); }
  double Y(double y) const { return top + height * (1.0 - (y - y0) / (y1 - y0)); }
};

/// The box, its title above and the data range at its ends.
std::string SvgAxes(const PlotBox& box, const std::string& title, const std::string& x_label,
                    const std::string& y_label) {
  const double bottom = box.top + box.height, right = box.left + box.width;
  return SvgFrame(box.left, box.top, box.width, box.height) +
         SvgText(box.left, box.top - 8, title) + SvgText(box.left, bottom + 16, Decimal(box.x0)) +
         SvgText(right, bottom + 16, Decimal(box.x1), "end") +
         SvgText(0.5 * (box.left + right), bottom + 32, x_label, "middle") +
         SvgText(box.left - 4, bottom, Decimal(box.y0), "end") +
         SvgText(box.left - 4, box.top + 10, Decimal(box.y1), "end") +
         SvgText(box.left - 4, box.top + 26, y_label, "end");
}

/// The corners of the used views as dots over the image scaled by `scale`, per view a
/// group named after the view (a viewer shows the name on hover).
std::string SvgCornerDots(const IntrinsicsCalibrationResult& result, double left, double top,
                          double scale) {
  std::string svg;
  for (size_t i = 0; i < result.views.size(); ++i) {
    const ViewReport& view = result.views[i];
    if (!view.used) continue;
    svg += "<g fill=\"" + ViewColour(i, result.views.size()) + "\"><title>" +
           MarkupEscape(view.name) + "</title>\n";
    for (const cv::Point2f& p : view.corners_px) {
      svg += "<circle cx=\"" + Decimal(left + scale * p.x) + "\" cy=\"" +
             Decimal(top + scale * p.y) + "\" r=\"2\"/>\n";
    }
    svg += "</g>\n";
  }
  return svg;
}

std::string SvgCoverageCells(const CoverageGrid& grid, double left, double top, double scale) {
  std::string svg;
  const double cell_w = scale * grid.width / grid.cols, cell_h = scale * grid.height / grid.rows;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const bool empty = grid.corners[static_cast<size_t>(r * grid.cols + c)] == 0;
      svg += "<rect x=\"" + Decimal(left + c * cell_w) + "\" y=\"" + Decimal(top + r * cell_h) +
             "\" width=\"" + Decimal(cell_w) + "\" height=\"" + Decimal(cell_h) + "\" fill=\"" +
             (empty ? "#f6c6c6" : "none") + "\" stroke=\"#bbbbbb\"/>\n";
    }
  }
  return svg;
}

/// The residual vectors of the used views, `magnify` x their length, from their corners.
std::string SvgResidualVectors(const IntrinsicsCalibrationResult& result, double left, double top,
                               double scale, double magnify) {
  std::string svg = "<g stroke-width=\"1\">\n";
  for (size_t i = 0; i < result.views.size(); ++i) {
    const ViewReport& view = result.views[i];
    if (!view.used) continue;
    svg += "<g stroke=\"" + ViewColour(i, result.views.size()) + "\">\n";
    for (size_t k = 0; k < view.corners_px.size() && k < view.residuals_px.size(); ++k) {
      const cv::Point2f& p = view.corners_px[k];
      const cv::Point2f& r = view.residuals_px[k];
      svg += "<line x1=\"" + Decimal(left + scale * p.x) + "\" y1=\"" + Decimal(top + scale * p.y) +
             "\" x2=\"" + Decimal(left + scale * p.x + magnify * r.x) + "\" y2=\"" +
             Decimal(top + scale * p.y + magnify * r.y) + "\"/>\n";
    }
    svg += "</g>\n";
  }
  return svg + "</g>\n";
}

std::string ResidualVectorPanel(const IntrinsicsCalibrationResult& result,
                                const ResidualSamples& samples, double left, double top,
                                double panel_width) {
  const double scale = panel_width / result.camera.width;
  // The 95th percentile residual drawn 20 px long: visible, yet short of the next corner.
  const double typical = std::max(1e-6, Percentile(samples.length_px, 0.95));
  const double magnify = 20.0 / typical;
  return SvgFrame(left, top, panel_width, scale * result.camera.height) +
         SvgText(left, top - 8,
                 "residual vectors (found - reprojected) x" + Decimal(magnify / scale, 0)) +
         SvgResidualVectors(result, left, top, scale, magnify);
}

std::string ResidualRadiusPanel(const ResidualSamples& samples, const PlotBox& area) {
  PlotBox box = area;
  box.x1 = std::max(1.0, LargestOf(samples.radius_px));
  box.y1 = std::max(1e-3, LargestOf(samples.length_px));
  std::string svg =
      SvgAxes(box, "residual length against radius", "distance from (cx, cy), px", "px");
  svg += "<g fill=\"#1f5fa8\" fill-opacity=\"0.5\">\n";
  for (size_t k = 0; k < samples.length_px.size(); ++k) {
    svg += "<circle cx=\"" + Decimal(box.X(samples.radius_px[k])) + "\" cy=\"" +
           Decimal(box.Y(samples.length_px[k])) + "\" r=\"1.5\"/>\n";
  }
  return svg + "</g>\n";
}

/// The expected count per bin of `count` normal samples of `sigma`, as a polyline.
std::string SvgNormalCurve(const PlotBox& box, size_t count, double sigma, double bin_width) {
  if (!(sigma > 0)) return "";
  std::string points;
  for (int k = 0; k <= 100; ++k) {
    const double x = box.x0 + (box.x1 - box.x0) * k / 100.0;
    const double density =
        std::exp(-0.5 * x * x / (sigma * sigma)) / (sigma * std::sqrt(2.0 * std::numbers::pi));
    points += Decimal(box.X(x)) + "," + Decimal(box.Y(count * bin_width * density)) + " ";
  }
  return "<polyline fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.5\" points=\"" + points +
         "\"/>\n";
}

std::string ResidualHistogramPanel(const ResidualSamples& samples, double sigma,
                                   const PlotBox& area) {
  constexpr int kBins = 24;
  PlotBox box = area;
  const double spread = sigma > 0 ? sigma : std::max(1e-3, Percentile(samples.length_px, 0.68));
  box.x0 = -4.0 * spread;
  box.x1 = 4.0 * spread;
  const std::vector<int> counts = Histogram(samples.components_px, box.x1, kBins);
  box.y1 = std::max(1, *std::max_element(counts.begin(), counts.end()));
  const double bin_width = (box.x1 - box.x0) / kBins;
  std::string svg = SvgAxes(box, "x, y components; red: normal of s " + Decimal(spread, 4) + " px",
                            "px", "count");
  for (int b = 0; b < kBins; ++b) {
    const double x = box.x0 + b * bin_width;
    svg += "<rect x=\"" + Decimal(box.X(x)) + "\" y=\"" + Decimal(box.Y(counts[b])) +
           "\" width=\"" + Decimal(box.X(x + bin_width) - box.X(x)) + "\" height=\"" +
           Decimal(box.Y(0) - box.Y(counts[b])) + "\" fill=\"#9fb8d8\" stroke=\"white\"/>\n";
  }
  return svg + SvgNormalCurve(box, samples.components_px.size(), spread, bin_width);
}

std::string HtmlParameterTable(const IntrinsicsCalibrationResult& result) {
  std::string html =
      "<table>\n<tr><th>parameter</th><th>value</th><th>1-sigma</th><th>unit</th></tr>\n";
  for (const ParameterRow& row : ParameterRows(result)) {
    html += "<tr><td>" + row.name + "</td><td>" + Decimal(row.value, 6) + "</td><td>" +
            (row.has_sigma ? Decimal(row.sigma, 6) : std::string("-")) + "</td><td>" +
            (row.unit.empty() ? std::string("-") : row.unit) + "</td></tr>\n";  // "-": no unit
  }
  return html + "</table>\n";
}

std::string HtmlViewTable(const IntrinsicsCalibrationResult& result) {
  std::string html =
      "<table>\n<tr><th>view</th><th>corners</th><th>RMS, px</th><th>tilt, deg</th>"
      "<th>in the fit</th></tr>\n";
  for (const ViewReport& view : result.views) {
    // Every cell says something: an empty last column read as a layout fault (issue 43).
    const std::string note = std::string(view.outlier ? "outlier, " : "") +
                             (view.used ? "used" : "dropped");
    html += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                        MarkupEscape(view.name), view.points, Decimal(view.rms_px, 4),
                        Decimal(view.tilt_deg, 1), note);
  }
  return html + "</table>\n";
}

std::string HtmlFigure(const std::string& file, const std::string& caption) {
  // A relative URL, never a bare name: a file named "javascript:...svg" would be a script.
  const std::string url = RelativeFileUrl(file);
  return "<figure><a href=\"" + url + "\"><img src=\"" + url + "\" alt=\"" +
         MarkupEscape(caption) + "\"></a><figcaption>" + MarkupEscape(caption) +
         "</figcaption></figure>\n";
}

}  // namespace

std::vector<ParameterRow> ParameterRows(const IntrinsicsCalibrationResult& result) {
  const CameraIntrinsics& camera = result.camera;
  std::vector<ParameterRow> rows = {{"fx", camera.K(0, 0), 0, false, "px"},
                                    {"fy", camera.K(1, 1), 0, false, "px"},
                                    {"cx", camera.K(0, 2), 0, false, "px"},
                                    {"cy", camera.K(1, 2), 0, false, "px"}};
  const std::vector<std::string> names = DistortionCoefficientNames(result.model);
  for (Eigen::Index i = 0; i < camera.distortion.size(); ++i) {
    const size_t k = static_cast<size_t>(i);
    rows.push_back(
        {k < names.size() ? names[k] : fmt::format("d{}", i), camera.distortion(i), 0, false, ""});
  }
  if (const auto& covariance = camera.intrinsics_covariance) {
    for (size_t i = 0; i < rows.size() && static_cast<Eigen::Index>(i) < covariance->rows(); ++i) {
      const auto j = static_cast<Eigen::Index>(i);
      rows[i].sigma = std::sqrt(std::max(0.0, (*covariance)(j, j)));
      rows[i].has_sigma = true;
    }
  }
  return rows;
}

int CoverageGrid::EmptyCells() const {
  return static_cast<int>(std::count(corners.begin(), corners.end(), 0));
}

int CoverageGrid::CellOf(double u, double v) const {
  const int c = std::clamp(static_cast<int>(std::floor(u * cols / width)), 0, cols - 1);
  const int r = std::clamp(static_cast<int>(std::floor(v * rows / height)), 0, rows - 1);
  return r * cols + c;
}

CoverageGrid CornerCoverage(const IntrinsicsCalibrationResult& result, int cols, int rows) {
  CoverageGrid grid;
  grid.cols = cols;
  grid.rows = rows;
  grid.width = std::max(1, result.camera.width);
  grid.height = std::max(1, result.camera.height);
  grid.corners.assign(static_cast<size_t>(cols * rows), 0);
  for (const ViewReport& view : result.views) {
    if (!view.used) continue;
    for (const cv::Point2f& p : view.corners_px) ++grid.corners[grid.CellOf(p.x, p.y)];
  }
  return grid;
}

std::string CoverageSummary(const CoverageGrid& grid) {
  const int cells = grid.cols * grid.rows;
  std::string text = fmt::format("corners in {} of {} cells of the {} x {} grid over the image",
                                 cells - grid.EmptyCells(), cells, grid.cols, grid.rows);
  if (grid.EmptyCells() == 0) return text + "; no empty cell";
  text += "; empty (row, column from the top left):";
  for (int i = 0; i < cells; ++i) {
    if (grid.corners[static_cast<size_t>(i)] != 0) continue;
    text += fmt::format(" ({}, {})", i / grid.cols, i % grid.cols);
  }
  return text;
}

ResidualSamples CollectResiduals(const IntrinsicsCalibrationResult& result) {
  ResidualSamples samples;
  const double cx = result.camera.K(0, 2), cy = result.camera.K(1, 2);
  for (const ViewReport& view : result.views) {
    if (!view.used) continue;
    for (size_t k = 0; k < view.corners_px.size() && k < view.residuals_px.size(); ++k) {
      const cv::Point2f& r = view.residuals_px[k];
      samples.length_px.push_back(std::hypot(r.x, r.y));
      samples.radius_px.push_back(std::hypot(view.corners_px[k].x - cx, view.corners_px[k].y - cy));
      samples.components_px.push_back(r.x);
      samples.components_px.push_back(r.y);
    }
  }
  return samples;
}

std::vector<int> Histogram(const std::vector<double>& values, double limit, int bins) {
  std::vector<int> counts(static_cast<size_t>(std::max(1, bins)), 0);
  const int last = static_cast<int>(counts.size()) - 1;
  for (double value : values) {
    const int bin = static_cast<int>(std::floor((value + limit) / (2.0 * limit) * (last + 1)));
    ++counts[static_cast<size_t>(std::clamp(bin, 0, last))];
  }
  return counts;
}

std::string CoverageSvg(const IntrinsicsCalibrationResult& result, const CoverageGrid& grid) {
  constexpr double kLeft = 20, kTop = 40, kDrawnWidth = 800;
  const double scale = kDrawnWidth / grid.width;
  const double drawn_height = scale * grid.height;
  const int height = static_cast<int>(kTop + drawn_height + 50);
  return SvgHeader(static_cast<int>(kDrawnWidth + 2 * kLeft), height) +
         SvgText(kLeft, 24,
                 fmt::format("corners found, {} views (one colour each), image {} x {} px; red "
                             "cells: no corner",
                             result.views_used, grid.width, grid.height)) +
         SvgCoverageCells(grid, kLeft, kTop, scale) +
         SvgFrame(kLeft, kTop, kDrawnWidth, drawn_height) +
         SvgCornerDots(result, kLeft, kTop, scale) +
         SvgText(kLeft, kTop + drawn_height + 24, CoverageSummary(grid)) + "</svg>\n";
}

std::string ResidualsSvg(const IntrinsicsCalibrationResult& result) {
  const ResidualSamples samples = CollectResiduals(result);
  constexpr double kTop = 40, kPanelWidth = 420, kGap = 80;
  const double image_height = kPanelWidth * result.camera.height / std::max(1, result.camera.width);
  PlotBox radius_box;
  radius_box.left = kPanelWidth + kGap + 30;
  radius_box.top = kTop;
  radius_box.width = kPanelWidth - 60;
  radius_box.height = image_height;
  PlotBox histogram_box = radius_box;
  histogram_box.left = radius_box.left + kPanelWidth + kGap - 30;
  const int width = static_cast<int>(histogram_box.left + histogram_box.width + 20);
  const int height = static_cast<int>(kTop + image_height + 60);
  return SvgHeader(width, height) + ResidualVectorPanel(result, samples, 20, kTop, kPanelWidth) +
         ResidualRadiusPanel(samples, radius_box) +
         ResidualHistogramPanel(samples, result.residual_sigma_px, histogram_box) + "</svg>\n";
}

std::string ReportHtml(const IntrinsicsCalibrationResult& result, const CoverageGrid& grid,
                       const ReportFiles& files) {
  const std::string title = "Intrinsics calibration: " + MarkupEscape(files.camera_yaml);
  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + title +
      "</title>\n<style>body{font-family:sans-serif;max-width:1400px;margin:1em auto;"
      "padding:0 1.5em}"
      "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;"
      "text-align:right}img{max-width:100%}</style></head><body>\n<h1>" +
      title + "</h1>\n";
  html += fmt::format(
      "<p>Image {} x {} px, model {}, {} of {} views used. Reprojection RMS <b>{} px</b> (median "
      "per view {} px).</p>\n",
      result.camera.width, result.camera.height, ToString(result.model), result.views_used,
      result.views.size(), Decimal(result.rms_px, 4), Decimal(result.median_view_rms_px, 4));
  html += "<h2>Parameters</h2>\n" + HtmlParameterTable(result);
  html +=
      "<p>1-sigma from the fit's Jacobian: the intrinsics' block of (J<sup>T</sup>J)"
      "<sup>-1</sup> with the board poses marginalised (Schur complement), scaled by the "
      "residual variance s<sup>2</sup> = |r|<sup>2</sup> / (residuals - parameters), s = " +
      Decimal(result.residual_sigma_px, 4) +
      " px. It assumes the residuals are independent noise; a model that cannot describe "
      "the lens shows in the residual plot as structure, not in the sigmas.</p>\n";
  html += "<h2>Coverage</h2>\n<p>" + MarkupEscape(CoverageSummary(grid)) + "</p>\n" +
          HtmlFigure(files.coverage_svg, "where the corners fell in the image");
  html += "<h2>Residuals</h2>\n" +
          HtmlFigure(files.residuals_svg, "residual vectors, against radius, histogram");
  html += "<h2>Views</h2>\n" + HtmlViewTable(result);
  // Relative URLs (issue 42 point 18: a camera file named "javascript:alert(1);x.yaml" made
  // every bare-name link a script).
  html += "<p>Files: <a href=\"" + RelativeFileUrl(files.camera_yaml) + "\">" +
          MarkupEscape(files.camera_yaml) + "</a>, <a href=\"" +
          RelativeFileUrl(files.text_report) + "\">" + MarkupEscape(files.text_report) +
          "</a> (the console report).</p>\n";
  return html + "</body></html>\n";
}

}  // namespace h4::cam
