// The camera section's tables (see report_camera.h).
#include "host/report/report_camera.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <spdlog/fmt/fmt.h>

#include "common/text/markup_escape.h"
#include "host/report/html_table.h"

namespace h4::host {
namespace {

// Focal lengths and principal point in px; distortion coefficients, unitless, to more digits.
std::string IntrinsicValue(const std::string& name, double value) {
  const bool pixels = name == "camera.fx" || name == "camera.fy" || name == "camera.cx" ||
                      name == "camera.cy";
  return pixels ? fmt::format("{:.3f}", value) : fmt::format("{:.6g}", value);
}

std::string RefinedRows(const ResultCamera& camera) {
  std::string t;
  for (const ResultCameraParameter& p : camera.parameters) {
    const double change = p.value - p.file_value;
    if (!p.std) {
      t += Row(MarkupEscape(p.name),
               {IntrinsicValue(p.name, p.file_value), IntrinsicValue(p.name, p.value), "", "",
                "kept: " + MarkupEscape(p.fixed_reason.empty() ? "fixed" : p.fixed_reason)},
               "fixed");
      continue;
    }
    t += Row(MarkupEscape(p.name),
             {IntrinsicValue(p.name, p.file_value), IntrinsicValue(p.name, p.value),
              IntrinsicValue(p.name, change), IntrinsicValue(p.name, *p.std),
              *p.std > 0 ? fmt::format("{:+.1f}", change / *p.std) : ""});
  }
  return t;
}

// The camera share at each map point: what the full variance has beyond the camera-exact
// one. The two maps are of the same model on the same grid; a point only one of them kept
// (a sigma not finite) is left out.
std::vector<double> SharePerPoint(const AccuracyMap& full, const AccuracyMap& exact) {
  std::vector<double> share;
  size_t next = 0;  // both lists are in the grid's order
  for (const AccuracyMapPoint& point : full.points) {
    size_t k = next;
    while (k < exact.points.size() && exact.points[k].x != point.x) ++k;
    if (k == exact.points.size()) continue;  // not in the camera-exact map
    next = k + 1;
    const double a = point.position_sigma_m, b = exact.points[k].position_sigma_m;
    share.push_back(std::sqrt(std::max(0.0, a * a - b * b)));
  }
  return share;
}

}  // namespace

std::string RefinedIntrinsicsTable(const ValidationInputs& in) {
  std::string t;
  for (const auto* result : {&in.result12, &in.result31}) {
    if (!result->has_value() || !(*result)->camera) continue;
    const ResultCamera& camera = *(*result)->camera;
    t += fmt::format(
        "<table>\n<caption>Model {}: {} {}x{}, refined on {} corners ({} rejected), corner "
        "residual {:.3f} px RMS per axis</caption>\n",
        ToString((*result)->model), MarkupEscape(camera.distortion_model), camera.width,
        camera.height, camera.corners, camera.rejected_corners, camera.corner_rms_px);
    t += Header({"intrinsic", "camera file", "refined", "refined - file", "1 sigma",
                 "(refined - file) / sigma"}) +
         RefinedRows(camera) + "</table>\n";
  }
  return t;
}

std::string CameraShareTable(const ValidationReport& report) {
  std::string t;
  bool any = false;
  for (const ModelValidation& v : report.models) {
    if (!v.accuracy_map || !v.accuracy_map_camera_exact) continue;
    const std::vector<double> share = SharePerPoint(*v.accuracy_map, *v.accuracy_map_camera_exact);
    if (share.empty()) continue;
    if (!any) {
      t += "<table>\n" +
           Header({"", "median 1-sigma (mm)", "largest (mm)", "intrinsics exact: median (mm)",
                   "largest (mm)", "camera's share: median (mm)", "largest (mm)"});
      any = true;
    }
    std::vector<double> sorted = share;
    std::sort(sorted.begin(), sorted.end());
    const auto mm = [](double m) { return fmt::format("{:.4f}", m * 1e3); };
    t += Row(MarkupEscape(v.label),
             {mm(v.accuracy_map->MedianPositionSigma()), mm(v.accuracy_map->MaxPositionSigma()),
              mm(v.accuracy_map_camera_exact->MedianPositionSigma()),
              mm(v.accuracy_map_camera_exact->MaxPositionSigma()), mm(sorted[sorted.size() / 2]),
              mm(sorted.back())});
  }
  if (any) t += "</table>\n";
  return t;
}

std::string CornerResidualSummary(const CornerResidualMap& map) {
  double largest = 0.0;
  for (const CornerResidualCell& cell : map.cells) largest = std::max(largest, cell.mean_px.norm());
  return fmt::format(
      "<p>{} corners of {} poses predicted through the Model {} result and {} ({} poses left "
      "out: rejected by the result, or their forward kinematics failed): residual {:.3f} px "
      "RMS per axis; {:.3f} px within half the half-diagonal of the image centre, {:.3f} px "
      "beyond; the largest cell mean is {:.3f} px.</p>\n",
      map.corners, map.poses, ToString(map.model),
      map.refined_camera ? "the intrinsics the corner path refined"
                         : "the camera file's intrinsics (a pose-path result)",
      map.poses_left_out, map.rms_px, map.inner_rms_px, map.outer_rms_px, largest);
}

}  // namespace h4::host
